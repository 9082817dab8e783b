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

}  // namespace esif
