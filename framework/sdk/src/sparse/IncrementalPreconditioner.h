#pragma once
/// \file IncrementalPreconditioner.h
/// Incomplete-Cholesky preconditioner M = P^T L~ L~^T P ~= I maintained
/// across updates as in book Sec. 3.3.1.1, eq. (3.27)-(3.31), App. B.2:
///  - Case (i), the updates since the last refresh touch only positions
///    >= p and the trailing dimension is below n0: the leading columns of
///    L~ (L~11 and L~21) are kept as they are, and the trailing block is
///    replaced by an incomplete factor of H_R + L~22 L~22^T, eq. (3.31).
///    L~ is stored column by column (LowerCsc), so the trailing block is
///    exactly the tail of its arrays: cut at column p, append the new
///    block. H_R is the sum of the C C^T of the logged updates; L~22 L~22^T
///    is accumulated column by column; new variables take the next positions
///    with zero rows in L~21 (they couple only with updated variables).
///  - Case (ii): the variables are reordered (distance or CAMD) and the
///    whole reordered I gets a fresh incomplete factorisation.

#include "sparse/Cholmod.h"
#include <esif/sparse/InformationForm.h>
#include <esif/sparse/LowerCsc.h>
#include <esif/sparse/SparseCounters.h>
#include <esif/sparse/SparseRecoveryParams.h>
#include "sparse/TrailingUpdates.h"
#include "sparse/VariableOrdering.h"

#include <Eigen/Core>

namespace esif
{
class IncrementalPreconditioner
{
   public:
	/// `common` (for CAMD) and `counters` must outlive this object.
	IncrementalPreconditioner(const SparseRecoveryParams& params, SparseCounters& counters, CholmodCommon& common);

	/// Logs an update already applied to `info`.
	void noteUpdate(const InformationForm& info, const UpdateTerm& term);
	/// An earlier update was subtracted: the next refresh factors afresh.
	void noteWithdrawal() { updates_.overflow(); }

	/// Case (i) or (ii) as described above. Throws NumericalError when a
	/// pivot breaks down (I not numerically positive definite).
	void refresh(const InformationForm& info, const Eigen::Vector2d& reference);

	/// z = M^-1 r (natural order).
	void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

	/// Non-zeros of L~ (lower triangle with diagonal).
	std::size_t nonZeros() const { return L_.nonZeros(); }
	/// L~ (positions).
	const LowerCsc& factor() const { return L_; }
	/// Position of scalar g in the current ordering.
	int position(int g) const { return ordering_.position[g]; }

   private:
	void factorAfresh(const InformationForm& info, const Eigen::Vector2d& reference);
	void refactorTrailingPart(const InformationForm& info);
	LowerCsc trailingMatrix(int p, int n) const;
	LowerCsc factorChecked(const LowerCsc& A, int first_position, const InformationForm& info);

	const SparseRecoveryParams& params_;
	SparseCounters& counters_;
	CholmodCommon& common_;
	LowerCsc L_;  ///< L~, positions
	ScalarOrdering ordering_;
	int factored_dim_ = 0;
	TrailingUpdates updates_;
	mutable Eigen::VectorXd work_;
};

}  // namespace esif
