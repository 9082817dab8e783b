#pragma once
/// \file DslamSequenceFeeder.h
/// Turns DslamLikeSequence steps into variables and EIF updates of a
/// SparseInformationCore, as a D-SLAM mapper would (book Sec. 3.1.3).

#include <esif/sparsebench/DslamLikeSequence.h>
#include <esif/sparse/SparseInformationCore.h>

#include <vector>

namespace esif
{
class DslamSequenceFeeder
{
   public:
	/// Adds the step's new features, initialised from the reference's
	/// estimate and their z (like eq. 3.14), the anchor prior on the first
	/// step, and the step's measurement (eq. 3.15); the robot becomes the
	/// reference point for reorderings.
	void apply(const DslamStep& step, const DslamLikeSequence& sequence, SparseInformationCore& core);

	/// Variable of a mapped feature.
	VarId variable(int feature) const { return VarId{var_of_[feature]}; }
	/// Features mapped so far.
	int mappedFeatures() const { return mapped_; }

   private:
	std::vector<int> var_of_;
	int mapped_ = 0;
};

}  // namespace esif
