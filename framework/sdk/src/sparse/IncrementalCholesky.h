#pragma once
/// \file IncrementalCholesky.h
/// Recovery by a complete Cholesky factor kept current across updates
/// (book Sec. 3.3.2, eq. 3.32-3.37, App. B.1), with SuiteSparse CHOLMOD.
///
/// The factor is a simplicial LDL^T of P A P^T, where A is I bordered by
/// identity "padding" rows/columns for variables still to come and P
/// puts the padding rows last. Between two reorderings:
///  - An update I += C C^T touching only positions >= p leaves L11 and L21
///    (columns < p) unchanged; the trailing block becomes the factor of
///    H_R + L22 D22 L22^T, eq. (3.35)/(B.6). cholmod_updown computes exactly
///    that, as a rank-k modification of the trailing columns (only those on
///    the elimination-tree paths of C's rows), so the leading factor is kept
///    by construction and the trailing refactorisation costs O(k x fill of
///    the touched path), not a factorisation of the whole trailing block.
///  - A new variable takes the next padding positions (still trailing): its
///    rows join the update at those identity rows, and a rank-one downdate
///    per new scalar takes the padding's 1 back off the diagonal.
///  - The forward solution y = L^-1 P i is carried along by the _solve
///    variants of both calls (only its modified trailing entries change), so
///    the state costs one backward substitution, eq. (3.37), or, read on
///    demand, the part of it on the elimination-tree paths of the variables
///    read (solveStateAt, EliminationTreeSolves.h).
///  - After a modification only the pivots on the paths of the touched rows
///    changed, and only those are checked (PivotCheck.h).
/// The variables are reordered and factored afresh (Case ii) when the
/// padding rows run out, and by reorder_trigger: the book's, when the
/// touched trailing part reaches n0 scalars, or when the factor has filled in
/// by max_fill_growth beyond the fresh factor's non-zeros per scalar.

#include "sparse/Cholmod.h"
#include "sparse/EliminationTreeSolves.h"
#include "sparse/RecoverySolver.h"
#include <esif/sparse/SparseCounters.h>
#include <esif/sparse/SparseRecoveryParams.h>
#include "sparse/TrailingUpdates.h"
#include "sparse/VariableOrdering.h"

namespace esif
{
class IncrementalCholesky : public RecoverySolver
{
   public:
	/// `common` (one per core) and `counters` must outlive this object.
	IncrementalCholesky(const SparseRecoveryParams& params, SparseCounters& counters, CholmodCommon& common);

	void noteUpdate(const InformationForm& info, const UpdateTerm& term) override;
	void noteWithdrawal() override { updates_.overflow(); }
	/// Only the columns on the elimination-tree paths of the requested
	/// positions (EliminationTreeSolves.h), not O(nnz(L)).
	Eigen::MatrixXd solveCovarianceBlock(const InformationForm& info, const std::vector<int>& scalars) override;
	void refresh(const InformationForm& info, const Eigen::Vector2d& reference) override;
	void solveState(const InformationForm& info, Eigen::VectorXd& x) override;
	bool solvesStatePartially() const override;
	Eigen::VectorXd solveStateAt(const std::vector<int>& scalars) override;
	Eigen::MatrixXd solveColumns(const InformationForm& info, const std::vector<int>& scalars) override;
	cholmod_factor* choleskyFactor() override { return L_.get(); }
	std::size_t factorNonZeros() const override;

	/// Dimension of the factor including padding rows.
	int capacity() const { return capacity_; }
	/// Position of scalar g in the current ordering.
	int position(int g) const { return ordering_.position[g]; }

   private:
	void factorAfresh(const InformationForm& info, const Eigen::Vector2d& reference);
	void refactorTrailingPart(const InformationForm& info);
	/// Positions of the scalars the pending updates and new variables touch.
	std::vector<int> touchedPositions(const InformationForm& info) const;
	/// One pending update's columns in staircase form (StaircaseUpdate.h),
	/// row r at factor position positions[r] (ascending).
	struct PositionedColumns
	{
		std::vector<int> positions;
		Eigen::MatrixXd columns;
	};
	void applyPendingUpdates();
	/// `term` at its positions in staircase form; adds its delta_i to delta_b.
	PositionedColumns staircaseAtPositions(const TrailingUpdates::Term& term);
	/// The updates side by side as one CHOLMOD matrix of `rows` rows (null
	/// when they hold nothing).
	static CholmodSparsePtr packColumns(const std::vector<PositionedColumns>& updates, int rows, CholmodCommon& c);
	void removePaddingDiagonals(const InformationForm& info);
	void forwardSolve(const InformationForm& info);
	/// Checks every pivot of a fresh factor.
	void checkFactor(const InformationForm& info);
	/// The trailing dimension at which the update log gives up (n0 under the
	/// book's trigger; never below the factor's capacity otherwise).
	int trailingLimit() const;
	/// fill_growth: nnz(L) beyond (1 + max_fill_growth) x the fresh factor's,
	/// scaled by the scalars factored since.
	bool filledInTooMuch() const;

	const SparseRecoveryParams& params_;
	SparseCounters& counters_;
	CholmodCommon& common_;
	CholmodFactorPtr L_;
	CholmodDensePtr y_;        ///< L^-1 P [i; 0], positions
	CholmodDensePtr delta_b_;  ///< zero between calls (updown_solve workspace)
	CholmodDensePtr z_, x_;    ///< backward-solve results
	CholmodSolveWorkspace ws_;
	ScalarOrdering ordering_;
	int capacity_ = 0;
	int factored_dim_ = 0;     ///< scalars of I included in the factor
	double fresh_nnz_per_scalar_ = 0;  ///< nnz(L) / factored_dim_ right after the last fresh factorisation
	TrailingUpdates updates_;  ///< since the last refresh
	PartialBackSubstitution partial_;  ///< values of z = (D L^T)^-1 y read since the last refresh
};

}  // namespace esif
