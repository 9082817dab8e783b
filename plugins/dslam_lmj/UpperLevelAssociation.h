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
/// JCBB (or MRPT NN) with the exact joint test associates them
/// (associatePointSets). An unmatched local feature is new beyond a gate,
/// ambiguous (left out) within it.

#include "DslamLmjParams.h"

#include <esif/core/Estimate.h>
#include <esif/ekf/LandmarkEkf.h>
#include <esif/localmap/LocalMap.h>
#include <esif/localmap/MapLevelDecisions.h>
#include <esif/relative/FeatureMap.h>

#include <Eigen/Core>
#include <map>
#include <optional>
#include <set>
#include <vector>

namespace esif::lmj
{
struct UpperLevelOutcome
{
	/// One per local feature: Matched (global id), New (proposed id: the
	/// local one) or Rejected (ambiguous).
	StepReport decisions;
	/// What the search found (candidates, pairs dropped, JCBB nodes and
	/// fallbacks, ID-gate rejections); the fusion adds time and rejections.
	MapAssociationTally tally;
};

/// For each local feature, the global feature it is known to be before any
/// association: the same ID when IDs identify features, else the global
/// feature its ID was given when an earlier map was fused (the builder gives
/// a feature matched to the previous map that map's ID).
std::vector<std::optional<LandmarkId>> knownGlobalIds(
	const LocalMap& map, bool use_ids, const std::map<LandmarkId, LandmarkId>& global_of_local,
	const relative::FeatureMap& global);

/// Decisions by IDs: Matched when the global map has the ID, else New; but
/// an ID-matched local feature is Rejected (left out of the fusion) when,
/// in the frame of a reference pair of other ID-matched features (both
/// sides moved there, each with its own covariance, as for the
/// association), it fails the chi-square gate params.id_gate_chi2_quantile
/// (2 dof), or the pair's baseline length differs between the two maps
/// beyond the same quantile (1 dof; a frame fixes no scale). Rejected, not New: an ID names one feature, so a feature whose
/// position disagrees with its ID's carries a misread ID, and as a new
/// feature it would be a spurious one. A misread member of the pair would
/// make most others fail; then the pair is chosen again without it (first
/// without f1, then without f2) and the attempt with the fewest failures
/// is kept. Nothing is tested with fewer than three ID-matched features.
UpperLevelOutcome associateByIds(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, relative::FeatureMap& global, const DslamLmjParams& params);

/// Sec. 4.4.2 as above; nullopt when fewer than two known features can serve
/// as the pair. `local_cov` is the covariance of the local features (2n x 2n,
/// robot marginalised).
std::optional<UpperLevelOutcome> associateInPairFrame(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, const std::vector<std::optional<LandmarkId>>& known,
	relative::FeatureMap& global, const DslamLmjParams& params);

/// Sec. 4.4.2 without a known pair (upper_level_frame = start_pose): the
/// features `known` holds are Matched to it, as in associateInPairFrame;
/// every other local feature is associated with the global features near where `start` (the map's
/// start pose in the global frame, with its covariance) places it; the
/// candidates moved into the local map's frame with the first-order
/// covariance of the placement and of their own joint estimate (eq. 3.25
/// columns), then associated as in associateInPairFrame but given the
/// Matched ones, which join the joint test as anchors
/// (decideMapFeaturesGivenAnchors; docs/plugins/dslam_lmj.md has the
/// measurements). The placement's
/// error is taken as independent of the candidates' (it comes from the
/// previous map's pair, which is near some of them): the test is wider than
/// the exact one where they are correlated positively.
UpperLevelOutcome associateInStartFrame(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, const std::vector<std::optional<LandmarkId>>& known,
	const PoseEstimate& start, relative::FeatureMap& global, const DslamLmjParams& params);

/// Sec. 4.4.4's close rule without IDs (upper_level_frame = start_pose):
/// how many of the open map's own features, placed by `frame` (the open
/// map's start in the global frame), pass the individual gate
/// (`gate_quantile`, 2 dof) of some supported global feature. The
/// placement's and the feature's own uncertainty count; the global
/// feature's is left out, which would need a covariance recovery at every step.
std::size_t ownFeaturesPlacedInGlobalMap(const LandmarkEkf& open_map, const std::set<LandmarkId>& own_ids,
										 const PoseEstimate& frame, const relative::FeatureMap& global,
										 double gate_quantile);

/// The matches of `outcome` checked as associateByIds checks ID matches
/// (in the frame of a reference pair of them, id_gate_chi2_quantile): a
/// wrong match chosen as the fusion's pair would misplace the whole map, and
/// every map after it, since each starts where the last ended. A failing
/// match is Rejected (left out), and counted in pairs_dropped.
void rejectMatchesFailingPairGate(const LocalMap& map, const Eigen::MatrixXd& local_cov, relative::FeatureMap& global,
								  const DslamLmjParams& params, UpperLevelOutcome& outcome);

}  // namespace esif::lmj
