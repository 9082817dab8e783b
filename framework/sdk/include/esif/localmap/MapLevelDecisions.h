#pragma once
/// \file MapLevelDecisions.h
/// The three outcomes of a closed local map's features against the global
/// map, shared by SLSJF (Sec. 5.4.1) and D-SLAM map joining (Sec. 4.4.2):
/// the whole map is associated at once (JCBB, or MRPT NN, with the exact
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
#include <esif/core/Estimate.h>
#include <esif/localmap/MapLevelAssociationParams.h>

#include <string>
#include <utility>
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

/// As decideMapFeatures, for a map some of whose features are decided
/// already (anchors: matched by ID, e.g. by the scans' association with the
/// global map). `sets` holds the `undecided` points first and the anchors'
/// after them; its candidates the others first and, from
/// `first_anchor_candidate` on, the anchors' own global features in the
/// anchors' order. The anchors join the search's joint test and the
/// new-feature test, so the rest is decided given them: a map whose start
/// pose is uncertain (after a blind drive) can otherwise match its other
/// features by a rotation its anchors rule out, each pair compatible on its
/// own (MRCLAM robot 5, docs/plugins/slsjf.md). A point paired with an
/// anchor's feature is left out (poorly observed): that feature is the
/// anchor's. Returns the decisions of the `undecided` points only.
MapLevelDecisions decideMapFeaturesGivenAnchors(const PointSets& sets, std::size_t undecided,
												int first_anchor_candidate, const MapLevelAssociationParams& params);

/// What the map-level associations of a run found, the counters both
/// map-joining filters report (stats.json plugin_<name>): per fusion, and
/// summed over the run with +=.
struct MapAssociationTally
{
	double seconds = 0;	 ///< association_s
	std::size_t candidates = 0;	 ///< global features compared
	std::size_t pairs_dropped = 0;	///< MRPT pairs the exact joint test removed
	std::size_t features_rejected = 0;	///< local features left out (poorly observed, failed ID gate)
	std::size_t jcbb_nodes = 0;
	std::size_t jcbb_fallbacks = 0;	 ///< maps too ambiguous for JCBB (SearchBounds): nearest neighbour instead
	std::size_t id_gate_rejected = 0;  ///< ID-matched local features that failed the ID gate

	MapAssociationTally& operator+=(const MapAssociationTally& other);
	/// Appends association_s, association_candidates, association_pairs_dropped,
	/// features_rejected, jcbb_nodes, jcbb_fallbacks and id_gate_rejected.
	void appendCounters(std::vector<std::pair<std::string, double>>& counters) const;
};

/// Writes `result` into `decisions`: observed point u, the local feature
/// whose decision is `decisions.associations[slots[u]]`, becomes Matched to
/// `candidate_ids[result.candidate_of[u]]`, or Rejected (id -1) when poorly
/// observed; a new one keeps the decision it had (New, its proposed ID).
/// Adds the search's counters to `tally`.
void applyMapLevelDecisions(
	const MapLevelDecisions& result, const std::vector<int>& slots, const std::vector<LandmarkId>& candidate_ids,
	StepReport& decisions, MapAssociationTally& tally);

/// The number of Rejected decisions in `decisions` (features_rejected).
std::size_t rejectedCount(const StepReport& decisions);

}  // namespace esif
