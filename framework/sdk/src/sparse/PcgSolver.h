#pragma once
/// \file PcgSolver.h
/// Recovery by the preconditioned conjugate gradient method (book Sec.
/// 3.3.1) with the incrementally maintained incomplete-Cholesky
/// preconditioner of eq. (3.27)-(3.31). The state solve starts from the
/// previous estimate and covariance columns from zero (Sec. 3.3.1.2).

#include "sparse/IncrementalPreconditioner.h"
#include "sparse/RecoverySolver.h"

namespace esif
{
class PcgSolver : public RecoverySolver
{
   public:
	/// `common` (for CAMD) and `counters` must outlive this object.
	PcgSolver(const SparseRecoveryParams& params, SparseCounters& counters, CholmodCommon& common);

	void noteUpdate(const InformationForm& info, const UpdateTerm& term) override;
	void noteWithdrawal() override { preconditioner_.noteWithdrawal(); }
	void refresh(const InformationForm& info, const Eigen::Vector2d& reference) override;
	void solveState(const InformationForm& info, Eigen::VectorXd& x) override;
	Eigen::MatrixXd solveColumns(const InformationForm& info, const std::vector<int>& scalars) override;
	std::size_t factorNonZeros() const override { return preconditioner_.nonZeros(); }
	const LowerCsc* incompleteFactor() const override { return &preconditioner_.factor(); }

   private:
	/// Solves I x = b from the given x; returns the iterations used.
	int solve(const InformationForm& info, const Eigen::VectorXd& b, Eigen::VectorXd& x, const std::string& what);

	const SparseRecoveryParams& params_;
	SparseCounters& counters_;
	IncrementalPreconditioner preconditioner_;
	Eigen::VectorXd r_, z_, p_, q_;
};

}  // namespace esif
