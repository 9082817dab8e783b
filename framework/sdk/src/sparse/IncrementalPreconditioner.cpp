#include <esif/core/Errors.h>
#include "sparse/IncompleteCholesky.h"
#include "sparse/IncrementalPreconditioner.h"
#include "sparse/PivotCheck.h"

#include <Eigen/Dense>

namespace esif
{
namespace
{
const std::string kPreconditionerWhat = "sparse recovery (PCG preconditioner)";

}  // namespace

IncrementalPreconditioner::IncrementalPreconditioner(const SparseRecoveryParams& params, SparseCounters& counters,
													 CholmodCommon& common)
	: params_(params), counters_(counters), common_(common)
{
}

void IncrementalPreconditioner::noteUpdate(const InformationForm& info, const UpdateTerm& term)
{
	updates_.record(info, term, ordering_.position, params_.n0);
}

void IncrementalPreconditioner::refresh(const InformationForm& info, const Eigen::Vector2d& reference)
{
	if (info.scalarDim() == 0) throw NumericalError(kPreconditionerWhat + ": the information form has no variables");
	if (updates_.overflowed())
		factorAfresh(info, reference);
	else if (!updates_.empty() || info.scalarDim() > factored_dim_)
		refactorTrailingPart(info);
}

LowerCsc IncrementalPreconditioner::factorChecked(const LowerCsc& A, int first_position, const InformationForm& info)
{
	auto ic = incompleteCholesky(A, params_.ic_drop_tolerance, params_.min_pivot_ratio);
	std::vector<double> pivots(first_position, 1.0);  // leading pivots are not re-examined
	pivots.insert(pivots.end(), ic.pivots.begin(), ic.pivots.end());
	checkPivots(pivots, first_position, ordering_.order, params_.min_pivot_ratio, info, kPreconditionerWhat);
	if (!ic.ok)
		throw NumericalError(kPreconditionerWhat + ": incomplete Cholesky broke down; lower ic_drop_tolerance (" +
							 std::to_string(params_.ic_drop_tolerance) + ")");
	return std::move(ic.L);
}

void IncrementalPreconditioner::factorAfresh(const InformationForm& info, const Eigen::Vector2d& reference)
{
	const int n = info.scalarDim();
	ordering_ = expandOrdering(info, reorderVariables(info, reference, params_, common_), n);
	try
	{
		L_ = factorChecked(info.matrix().permutedLower(ordering_.position, n), 0, info);
	}
	catch (...)
	{
		updates_.overflow();  // no usable factor: start over next time
		throw;
	}
	factored_dim_ = n;
	updates_.restart(n);
	++counters_.full_reorders;
}

LowerCsc IncrementalPreconditioner::trailingMatrix(int p, int n) const
{
	// H_R + L~22 L~22^T of eq. (3.31), on positions p..n-1 (local index
	// minus p). Dense: the block is below n0 scalars, and the product of
	// L~22 with itself fills most of it anyway; exact zeros are dropped.
	const int m = n - p;
	Eigen::MatrixXd S = Eigen::MatrixXd::Zero(m, m);
	for (int k = p; k < factored_dim_; ++k)
	{
		const int begin = L_.col_ptr[k], end = L_.col_ptr[k + 1];
		for (int a = begin; a < end; ++a)
			for (int b = begin; b <= a; ++b) S(L_.row_idx[a] - p, L_.row_idx[b] - p) += L_.values[a] * L_.values[b];
	}
	for (const auto& t : updates_.terms())
	{
		const Eigen::MatrixXd H = t.C * t.C.transpose();
		for (std::size_t a = 0; a < t.scalars.size(); ++a)
			for (std::size_t b = 0; b < t.scalars.size(); ++b)
			{
				const int pa = ordering_.position[t.scalars[a]] - p, pb = ordering_.position[t.scalars[b]] - p;
				if (pa >= pb) S(pa, pb) += H(a, b);
			}
	}
	return LowerCsc::fromDenseLower(S);
}

void IncrementalPreconditioner::refactorTrailingPart(const InformationForm& info)
{
	const int n = info.scalarDim(), p = updates_.start();
	// New variables take the next positions, in natural order.
	for (int g = factored_dim_; g < n; ++g) ordering_.append(g);
	try
	{
		const LowerCsc L22 = factorChecked(trailingMatrix(p, n), p, info);
		L_.truncateColumns(p, p);
		L_.appendColumns(L22, p);
	}
	catch (...)
	{
		updates_.overflow();
		throw;
	}
	factored_dim_ = n;
	updates_.restart(n);
	++counters_.partial_refactorisations;
}

void IncrementalPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const
{
	const int n = L_.n;
	work_.resize(n);
	for (int k = 0; k < n; ++k) work_[k] = r[ordering_.order[k]];
	L_.solveLower(work_);
	L_.solveLowerTransposed(work_);
	z.resize(n);
	for (int k = 0; k < n; ++k) z[ordering_.order[k]] = work_[k];
}

}  // namespace esif
