#pragma once
/// \file FreshCholesky.h
/// Reference recovery: a fill-reducing (AMD) CHOLMOD factorisation of the
/// whole I from scratch whenever I has changed, as a batch smoother (e.g.
/// square-root SAM, book Fig. 3.22) would do. Also the factor behind the
/// marginals of methods that keep no complete factor.

#include "sparse/Cholmod.h"
#include "sparse/RecoverySolver.h"
#include <esif/sparse/SparseCounters.h>
#include <esif/sparse/SparseRecoveryParams.h>

#include <vector>

namespace esif
{
class FreshCholesky : public RecoverySolver
{
   public:
	/// `common` (one per core) and `counters` must outlive this object.
	FreshCholesky(const SparseRecoveryParams& params, SparseCounters& counters, CholmodCommon& common);

	void noteUpdate(const InformationForm& info, const UpdateTerm& term) override { changed_ = true; }
	void noteWithdrawal() override { changed_ = true; }
	/// Factors afresh if anything changed; `reference` is not used.
	void refresh(const InformationForm& info, const Eigen::Vector2d& reference) override;
	void solveState(const InformationForm& info, Eigen::VectorXd& x) override;
	Eigen::MatrixXd solveColumns(const InformationForm& info, const std::vector<int>& scalars) override;
	cholmod_factor* choleskyFactor() override { return L_.get(); }
	std::size_t factorNonZeros() const override;

   private:
	const SparseRecoveryParams& params_;
	SparseCounters& counters_;
	CholmodCommon& common_;
	CholmodFactorPtr L_;
	CholmodDensePtr b_, x_;
	CholmodSolveWorkspace ws_;
	int factored_dim_ = 0;
	bool changed_ = true;
};

}  // namespace esif
