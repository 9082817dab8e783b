#pragma once
/// \file TrailingUpdates.h
/// The updates since the last factorisation and where they begin in the
/// variable ordering. Their sum is the H_R of eq. (3.27)/(3.32); the first
/// touched position p splits the factor into the part kept (columns < p)
/// and the trailing part to refactor. Once the trailing part reaches n0
/// scalars the log gives up (Case ii: reorder and factor afresh); so it
/// does when the updates' total rank passes 2 n0, which bounds its size.

#include <esif/sparse/InformationForm.h>

#include <Eigen/Core>
#include <vector>

namespace esif
{
class TrailingUpdates
{
   public:
	/// One update on natural scalar indices: I += C C^T, i += delta_i.
	struct Term
	{
		std::vector<int> scalars;
		Eigen::MatrixXd C;
		Eigen::VectorXd delta_i;
	};

	/// Starts over after a factorisation of the first `factored_dim` scalars.
	void restart(int factored_dim);

	/// Records `term`; `position[g]` is the position of the factored scalar
	/// g (g < factored dim); newer scalars go after all of them. When
	/// info.scalarDim() - start() reaches `limit` (n0 under the book's
	/// trigger) or the logged rank 2 `limit`,
	/// forgets everything and overflowed() becomes true.
	void record(const InformationForm& info, const UpdateTerm& term, const std::vector<int>& position, int limit);

	/// Forces Case (ii) (e.g. out of room for new variables).
	void overflow();

	bool overflowed() const { return overflowed_; }
	/// First position touched since the restart (the factored dim if none).
	int start() const { return start_; }
	const std::vector<Term>& terms() const { return terms_; }
	bool empty() const { return terms_.empty(); }

   private:
	std::vector<Term> terms_;
	int factored_dim_ = 0;
	int start_ = 0;
	int rank_ = 0;	///< columns of C logged
	bool overflowed_ = true;  ///< nothing factored yet
};

/// The columns of one update C, its rows sorted by position, recombined as
/// C Q (Q orthogonal: the same C C^T) into a lower staircase: column j
/// starts at the j-th touched position. cholmod_updown takes C eight
/// columns at a time and walks, for each group, the elimination-tree paths
/// from its columns' first rows to the root. As whitened (eq. 3.15, 5.9) a
/// dense measurement information makes nearly every column hold the
/// deepest variable of the update, so every group walks the longest path;
/// in staircase form only the first group does, the later ones start ever
/// higher, and an update with more columns than rows loses the excess. The
/// staircase is R^T from the QR factorisation of C^T (C C^T = R^T R).
Eigen::MatrixXd staircase(const Eigen::MatrixXd& C);

}  // namespace esif
