#include "sparse/TrailingUpdates.h"

#include <algorithm>

namespace esif
{
void TrailingUpdates::restart(int factored_dim)
{
	terms_.clear();
	rank_ = 0;
	factored_dim_ = factored_dim;
	start_ = factored_dim;
	overflowed_ = false;
}

void TrailingUpdates::overflow()
{
	terms_.clear();
	rank_ = 0;
	overflowed_ = true;
}

void TrailingUpdates::record(const InformationForm& info, const UpdateTerm& term, const std::vector<int>& position,
							 int limit)
{
	if (overflowed_) return;
	Term t{info.scalarIndices(term.vars), term.C, term.delta_i};
	for (int g : t.scalars) start_ = std::min(start_, g < factored_dim_ ? position[g] : factored_dim_);
	// C C^T has rank at most min(rows, columns): an update with more
	// measurement rows than scalars reaches cholmod_updown with one column
	// per scalar (staircase form, StaircaseUpdate.h).
	rank_ += static_cast<int>(std::min(t.C.rows(), t.C.cols()));
	// Dimension of H_R: from the first touched position to the end. Also
	// give up when the logged rank exceeds 2 limit: a rank-k modification of
	// the trailing part then costs more than factoring it afresh.
	if (info.scalarDim() - start_ >= limit || rank_ > 2 * limit)
	{
		overflow();
		return;
	}
	terms_.push_back(std::move(t));
}

}  // namespace esif
