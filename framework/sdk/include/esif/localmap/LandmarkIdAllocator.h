#pragma once
/// \file LandmarkIdAllocator.h
/// Global landmark IDs for the features a map-joining fusion declares new.
/// A new feature keeps the ID it proposes (its rawlog ID, or its local
/// map's) when that is free; otherwise it gets the lowest free ID above
/// every ID given so far, so IDs read from the rawlog and IDs given here
/// never meet twice.

#include <esif/core/StepInput.h>

#include <functional>

namespace esif
{
class LandmarkIdAllocator
{
   public:
	/// The ID of a new feature proposing `proposed` (negative: none);
	/// `taken(id)` says whether the global map, or the fusion under way,
	/// already uses id.
	LandmarkId allocate(LandmarkId proposed, const std::function<bool(LandmarkId)>& taken);

   private:
	LandmarkId next_free_ = 1;
};

}  // namespace esif
