#include <esif/core/Errors.h>
#include "sparse/FreshCholesky.h"
#include "sparse/PivotCheck.h"

namespace esif
{
namespace
{
const std::string kWhat = "sparse recovery (fresh Cholesky)";
}

FreshCholesky::FreshCholesky(const SparseRecoveryParams& params, SparseCounters& counters, CholmodCommon& common)
	: params_(params), counters_(counters), common_(common)
{
}

void FreshCholesky::refresh(const InformationForm& info, const Eigen::Vector2d&)
{
	const int n = info.scalarDim();
	if (n == 0) throw NumericalError(kWhat + ": the information form has no variables");
	if (L_ && !changed_ && n == factored_dim_) return;
	L_.reset();
	auto A = naturalLowerToCholmod(info.matrix(), n, common_);
	common_.useFillReducingOrdering();
	auto L = ownFactor(cholmod_analyze(A.get(), common_.get()), common_);
	if (!L) common_.check(kWhat + ": analysis");
	counters_.fresh_factor_flops += common_.get()->fl;
	cholmod_factorize(A.get(), L.get(), common_.get());
	common_.check(kWhat + ": factorisation");
	const auto* perm = static_cast<const int*>(L->Perm);
	checkPivots(factorPivots(*L), 0, std::vector<int>(perm, perm + n), params_.min_pivot_ratio, info, kWhat);
	L_ = std::move(L);
	factored_dim_ = n;
	changed_ = false;
	++counters_.full_reorders;
}

void FreshCholesky::solveState(const InformationForm& info, Eigen::VectorXd& x)
{
	const int n = info.scalarDim();
	if (!b_ || static_cast<int>(b_->nrow) != n) b_ = zeroDense(n, 1, common_);
	std::copy(info.vector().data(), info.vector().data() + n, static_cast<double*>(b_->x));
	cholmodSolve(CHOLMOD_A, L_.get(), b_.get(), x_, ws_, common_, kWhat + ": state");
	x = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(x_->x), n);
}

Eigen::MatrixXd FreshCholesky::solveColumns(const InformationForm& info, const std::vector<int>& scalars)
{
	const int n = info.scalarDim(), k = static_cast<int>(scalars.size());
	auto B = zeroDense(n, k, common_);
	for (int j = 0; j < k; ++j) static_cast<double*>(B->x)[static_cast<std::size_t>(j) * n + scalars[j]] = 1.0;
	CholmodDensePtr X;
	cholmodSolve(CHOLMOD_A, L_.get(), B.get(), X, ws_, common_, kWhat + ": covariance columns");
	return Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(X->x), n, k);
}

std::size_t FreshCholesky::factorNonZeros() const
{
	return L_ ? countFactorNonZeros(*L_, factored_dim_) : 0;
}

}  // namespace esif
