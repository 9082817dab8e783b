#pragma once
/// \file MapLevelDecisions.h
/// The three outcomes of a closed local map's features against the global
/// map, shared by SLSJF (Sec. 5.4.1) and D-SLAM map joining (Sec. 4.4.2):
/// the whole map is associated at once (MRPT JCBB or NN with the exact
/// joint test, associatePointSets), so a map of many features gives the
/// joint test something to work with where a scan of one feature does not;
/// then, as in the authors' I-SLSJF, a local feature is
/// - matched to its candidate;
/// - new when every candidate lies beyond new_feature_chi2_quantile;
/// - left out ("poorly observed", Rejected) in between: too close to a
///   candidate to be new, too far or too ambiguous to be it. It enters
///   neither map; a later local map that sees it better decides.
/// Where the candidates come from and in which frame they are compared is
/// the plugin's own.

#include <esif/association/PointSetAssociation.h>
#include <esif/localmap/MapLevelAssociationParams.h>

#include <vector>

namespace esif
{
enum class MapFeatureOutcome
{
	Matched,
	New,
	PoorlyObserved
};

struct MapLevelDecisions
{
	/// One per observed (local) point: its outcome and, when Matched, the
	/// index of its candidate.
	std::vector<MapFeatureOutcome> outcome;
	std::vector<int> candidate_of;
	std::size_t pairs_dropped = 0;	///< MRPT pairs the exact joint test removed
	std::size_t jcbb_nodes = 0;
	bool fell_back = false;	 ///< JCBB exceeded the search bounds: nearest neighbour instead
};

/// Associates `sets` with the method and gates of `params` (association
/// jcbb or auto: JCBB; nn: nearest neighbour) and decides each feature.
MapLevelDecisions decideMapFeatures(const PointSets& sets, const MapLevelAssociationParams& params);

}  // namespace esif
