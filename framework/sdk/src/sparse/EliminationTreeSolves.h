#pragma once
/// \file EliminationTreeSolves.h
/// Triangular solves on a simplicial LDL^T factor (CHOLMOD, row indices of
/// each column sorted, diagonal first) that touch only the columns on the
/// elimination-tree paths of the entries asked for.
///
/// Column j's first off-diagonal row is j's parent in the elimination tree,
/// and every row of column j is an ancestor of j. Hence
///  - L^-1 e_a is non-zero only on the path from a to the root, and
///  - in the back substitution D L^T z = y (eq. 3.37), z_j needs only the z
///    of j's ancestors.
/// A filter that reads a few variables between two updates (SLSJF reads the
/// features of the next local map) pays for their paths, which share the
/// top separators, instead of for every column of L.

#include <cholmod.h>

#include <Eigen/Core>
#include <vector>

namespace esif
{
/// The positions on the elimination-tree paths from `starts` to the roots,
/// ascending (the union of the paths, each position once).
std::vector<int> pathsToRoots(const cholmod_factor& L, const std::vector<int>& starts);

/// (L^-1 e_a)(j) / sqrt(d_j) for every a in `positions` (rows) and every j
/// in `reach` = pathsToRoots(L, positions) (columns): the covariance block
/// of `positions` is this matrix times its transpose, eq. (3.25).
Eigen::MatrixXd scaledForwardColumns(const cholmod_factor& L, const std::vector<int>& positions,
									 const std::vector<int>& reach);

/// z = (D L^T)^-1 y, eq. (3.37), at chosen positions only, each computed
/// over its ancestors and kept until invalidate(): later requests reuse the
/// shared top of the tree, so reading every position one at a time solves
/// each column once, as one whole back substitution would. The factor and y
/// must not change between invalidations.
class PartialBackSubstitution
{
   public:
	/// The factor or y changed: every kept value is stale.
	void invalidate() { ++epoch_; }
	/// z at `positions` of the factor L (n = L.n) with forward solution y.
	Eigen::VectorXd solveAt(const cholmod_factor& L, const double* y, const std::vector<int>& positions);
	/// Columns of L read since construction, for tests and counters.
	long columnsSolved() const { return columns_solved_; }

   private:
	bool known(int j) const { return stamp_[j] == epoch_; }

	std::vector<double> z_;
	std::vector<unsigned> stamp_;  ///< epoch_ where z_ holds this epoch's value
	std::vector<int> todo_;        ///< positions to solve in this request
	unsigned epoch_ = 1;
	long columns_solved_ = 0;
};

}  // namespace esif
