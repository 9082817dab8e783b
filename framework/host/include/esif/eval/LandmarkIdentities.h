#pragma once
/// \file LandmarkIdentities.h
/// Which true landmark each landmark of a final map stands for, when the
/// true landmark of each measurement is known (the rawlog's IDs, shown to
/// the filter or hidden from it, or the simulator's measurement truth): the
/// one most of its measurements came from (ties: the lowest true ID, as
/// AssociationAudit::filterToTrue). Several landmarks may stand for one
/// true landmark; the one that stands for it is the one with most of its
/// measurements (ties: the lowest landmark ID), the others are duplicates.

#include <esif/core/Estimate.h>
#include <esif/eval/AssociationAudit.h>
#include <esif/formats/LandmarkIdentityFile.h>

#include <map>
#include <vector>

namespace esif
{
/// One row per landmark of `map`, in its order: its identity from the
/// audit's votes, its votes for it and the measurements used on it (a
/// landmark the audit never saw has none of either).
LandmarkIdentities landmarkIdentities(const AssociationAudit& audit, const std::vector<LandmarkEstimate>& map);

/// True landmark -> the landmark of the map that stands for it, for every
/// true landmark some landmark is identified with; empty without truth.
std::map<LandmarkId, LandmarkId> primaryLandmarks(const LandmarkIdentities& identities);

}  // namespace esif
