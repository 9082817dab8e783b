#pragma once
/// \file UpperLevelAssociation.h
/// Which features of a closed local map are features of the global map
/// (book Sec. 4.4.2, upper level). No robot pose is needed: two local
/// features already known to be global ones (equal IDs, or matched to the
/// previous map by the local level) fix the local map relative to the
/// global one. Both maps are moved into the frame of that pair (PairFrame:
/// each side then depends on its own estimates only, so the two are
/// independent), the global candidates are pruned to the region the local
/// map can reach from f1 (its extent plus Delta from f1's global
/// uncertainty), only their covariance columns are recovered (eq. 3.25), and
/// MRPT JCBB or NN with the exact joint test associates them
/// (associatePointSets). An unmatched local feature is new beyond a gate,
/// ambiguous (left out) within it.

#include "DslamLmjParams.h"

#include <esif/core/Estimate.h>
#include <esif/localmap/LocalMap.h>
#include <esif/relative/FeatureMap.h>

#include <Eigen/Core>
#include <map>
#include <optional>
#include <vector>

namespace esif::lmj
{
struct UpperLevelOutcome
{
	/// One per local feature: Matched (global id), New (proposed id: the
	/// local one) or Rejected (ambiguous).
	StepReport decisions;
	std::size_t candidates = 0;
	std::size_t pairs_dropped = 0;
	std::size_t jcbb_nodes = 0;
};

/// For each local feature, the global feature it is known to be before any
/// association: the same ID when IDs identify features, else the global
/// feature its ID was given when an earlier map was fused (the builder gives
/// a feature matched to the previous map that map's ID).
std::vector<std::optional<LandmarkId>> knownGlobalIds(
	const LocalMap& map, bool use_ids, const std::map<LandmarkId, LandmarkId>& global_of_local,
	const relative::FeatureMap& global);

/// Decisions by IDs alone.
UpperLevelOutcome associateByIds(const LocalMap& map, const relative::FeatureMap& global);

/// Sec. 4.4.2 as above; nullopt when fewer than two known features can serve
/// as the pair. `local_cov` is the covariance of the local features (2n x 2n,
/// robot marginalised).
std::optional<UpperLevelOutcome> associateInPairFrame(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, const std::vector<std::optional<LandmarkId>>& known,
	relative::FeatureMap& global, const DslamLmjParams& params);

}  // namespace esif::lmj
