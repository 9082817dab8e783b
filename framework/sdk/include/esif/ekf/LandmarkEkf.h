#pragma once
/// \file LandmarkEkf.h
/// EKF SLAM over identified landmarks (book Sec. 1.2.1): the dense core plus
/// landmark identities and the data association of each scan (landmark IDs,
/// MRPT NN or MRPT JCBB). One implementation for the EKF plugin and the
/// local-map builder of the map-joining filters (Ch. 4-5), so both associate
/// exactly alike.
///
/// A step is: prediction with the odometry (eq. 1.8), association of the
/// scan, one joint update with every match (eq. 1.9-1.10, iterated when
/// the linear model does not fit the correction: IteratedUpdate in
/// EkfSlamCore.h), then the new landmarks initialised from their
/// measurements.
///
/// Landmark IDs are not trusted blindly: each ID-matched measurement is
/// tested on its own innovation against the prior (the chi-square gate
/// id_gate_chi2_quantile, 2 dof) before the joint update. Individually,
/// because a joint test over the scan only says that something is wrong,
/// and a wrong ID fused in the joint update moves the robot and with it
/// every other landmark of the scan; against the prior (its full
/// covariance, robot-landmark correlation included), because the test of a
/// measurement must not depend on whether the others were fused. The gate
/// is only as good as the filter's consistency: on a loop closed after
/// long dead reckoning, a plain EKF update linearised metres from the truth
/// leaves P far too small, and every later sighting fails the gate; the
/// iterated update is what keeps such valid measurements in. A
/// measurement failing the gate is Rejected. When its landmark has never
/// passed the gate since it was initialised, the one earlier sighting is
/// no more credible than this one (a misread ID of a landmark not yet
/// mapped creates it in the wrong place, and every correct measurement
/// would fail against it afterwards), so the landmark is marginalised out
/// too, and the next sighting of the ID initialises it anew. (Initialising
/// it from the failing measurement instead leaves it wrong whenever that
/// one was the misread and the landmark is not seen again: on grid196 with
/// 1% wrong IDs that made the landmark RMSE 1.47x the clean one, dropping
/// both 1.02x.)

#include <esif/association/TentativeFeatures.h>
#include <esif/core/Estimate.h>
#include <esif/ekf/CoincidentLandmarks.h>
#include <esif/ekf/EarlierFeatures.h>
#include <esif/ekf/EkfAssociationParams.h>
#include <esif/ekf/EkfSlamCore.h>
#include <esif/ekf/SightingRejections.h>

#include <algorithm>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace esif
{
class LandmarkEkf
{
   public:
	/// Robot at the origin with zero covariance. Landmarks the filter creates
	/// for measurements without an ID are numbered from `first_own_id` up,
	/// skipping IDs already in the map. `jacobians`: JacobianPoints of the core.
	explicit LandmarkEkf(const EkfAssociationParams& params = {}, LandmarkId first_own_id = 0,
						 JacobianPoints jacobians = JacobianPoints::Current);

	/// One step: predict, associate, update, add new landmarks. Returns one
	/// Association per measurement. Throws InputError when association =
	/// known_ids and a measurement has no ID, NumericalError on a failed update.
	StepReport processStep(const StepInput& step);

	/// Appends `features` as landmarks under their IDs, with their mean and
	/// joint covariance and no correlation with the rest of the state (known
	/// independently of it: the map-joining builder's association filter,
	/// LocalMapBuilder.h). Throws std::invalid_argument for an ID already
	/// mapped. They count as confirmed for the ID gate.
	void addPriorLandmarks(const EarlierFeatures& features);

	const EkfSlamCore& core() const { return core_; }
	/// Landmark IDs in the core's order (index i = landmark i).
	const std::vector<LandmarkId>& ids() const { return ids_; }
	/// The core index of landmark `id`, if mapped.
	std::optional<std::size_t> indexOf(LandmarkId id) const;
	/// The ID the next landmark created without a measured ID would get (or a larger one).
	LandmarkId nextOwnId() const { return next_own_id_; }
	/// Numbers the landmarks it creates without a measured ID above
	/// `largest_input_id` (FilterPlugin::reserveLandmarkIds).
	void reserveIdsUpTo(LandmarkId largest_input_id) { next_own_id_ = std::max(next_own_id_, largest_input_id + 1); }
	/// JCBB search nodes explored so far (MRPT's count).
	std::size_t jcbbNodes() const { return jcbb_nodes_; }
	/// Scans too ambiguous for JCBB (SearchBounds), associated by nearest
	/// neighbour with the joint compatibility test instead.
	std::size_t jcbbFallbacks() const { return jcbb_fallbacks_; }
	/// ID-matched measurements rejected by the ID gate.
	std::size_t idGateRejections() const { return id_gate_rejections_; }
	/// Landmarks marginalised out because a measurement failed the ID gate
	/// before any had confirmed them (the measurement is counted here, not
	/// in idGateRejections()).
	std::size_t idGateDrops() const { return id_gate_drops_; }
	/// Sightings associated by distance and left out, by cause.
	const SightingRejections& rejections() const { return rejections_; }
	/// Matches left out because another candidate was nearly as likely
	/// (EkfAssociationParams::ambiguity_margin_chi2_quantile).
	std::size_t ambiguousWaits() const { return rejections_.ambiguous_waits; }
	/// First sightings held as tentative landmarks, waiting for their second
	/// (EkfAssociationParams::confirm_new_landmarks).
	std::size_t tentativeCount() const { return tentative_.tentativeCount(); }
	/// Sightings held (and not fused) because no earlier one confirmed them.
	std::size_t unconfirmedSightings() const { return rejections_.unconfirmed; }
	/// Updates that were iterated (EkfAssociationParams::relinearise_above_d2).
	std::size_t iteratedUpdates() const { return iterated_updates_; }
	/// Their linearisations beyond the first.
	std::size_t relinearisations() const { return relinearisations_; }
	/// Iterated updates that stopped at an iterate raising the scan's cost.
	std::size_t iterationsStoppedUphill() const { return stopped_uphill_; }
	/// Landmarks merged into another (EkfAssociationParams::merge_landmarks_after_matches).
	std::size_t landmarkMerges() const { return coincident_.merges(); }
	/// The landmark that `id` has become by merges (itself if none).
	LandmarkId finalId(LandmarkId id) const { return coincident_.finalId(id); }

	PoseEstimate robotPose() const;
	/// Robot pose and every landmark with its marginal covariance.
	Estimate estimate() const;

   private:
	StepReport processUsableMeasurements(const StepInput& step);
	/// Association, joint update, unconfirmed landmarks dropped, new landmarks of step.scan.
	StepReport processScan(const StepInput& step);
	StepReport associateScan(const StepInput& step, std::vector<EkfSlamCore::Match>& matches);
	StepReport associateByIds(const StepInput& step, std::vector<EkfSlamCore::Match>& matches);
	/// Squared Mahalanobis distance of measurement `m` of landmark `index`
	/// from its prediction (covariance H P H^T + noise).
	double innovationDistance2(
		std::size_t index, const RangeBearing& m, const Eigen::Matrix2d& noise, const Pose2& sensor) const;
	/// Marginalises out the landmarks `indices` (their IDs leave the map).
	void dropLandmarks(std::vector<std::size_t> indices);
	/// Rebuilds index_of_ from ids_ after landmarks left the core.
	void reindex();
	StepReport associateByDistance(const Scan& scan, std::vector<EkfSlamCore::Match>& matches);
	std::vector<std::size_t> candidatesFor(const Scan& scan) const;
	/// Whether a candidate other than `chosen` is within the ambiguity margin of it for `m`.
	bool isAmbiguous(const Scan& scan, const RangeBearing& m, const std::vector<std::size_t>& candidates,
					 std::size_t chosen) const;
	void addNewLandmarks(const Scan& scan, std::size_t step, StepReport& report);
	/// Merges every pair of landmarks CoincidentLandmarks finds to be one point.
	void mergeCoincidentLandmarks();
	/// Whether a sighting without ID that would start a landmark is confirmed
	/// by an earlier one (TentativeFeatures); if not, it is held.
	bool confirmedSighting(const Scan& scan, const RangeBearing& m, std::size_t step);

	EkfAssociationParams params_;
	double gate_distance2_new_ = 0;	 // chi-square value of new_landmark_chi2_quantile
	double id_gate_distance2_ = 0;	// chi-square value of id_gate_chi2_quantile
	IteratedUpdate iterated_;
	EkfSlamCore core_;
	std::vector<LandmarkId> ids_;  // landmark index -> ID
	std::unordered_map<LandmarkId, std::size_t> index_of_;
	LandmarkId next_own_id_ = 0;
	/// IDs of the landmarks a measurement has passed the ID gate for (or that
	/// were matched by distance) since their initialisation.
	std::unordered_set<LandmarkId> confirmed_;
	std::vector<std::size_t> unconfirmed_failing_;	// landmark indices of this scan to drop
	std::size_t jcbb_nodes_ = 0;
	std::size_t jcbb_fallbacks_ = 0;
	std::size_t id_gate_rejections_ = 0;
	std::size_t id_gate_drops_ = 0;
	SightingRejections rejections_;
	TentativeFeatures tentative_;
	CoincidentLandmarks coincident_;
	std::size_t iterated_updates_ = 0;
	std::size_t relinearisations_ = 0;
	std::size_t stopped_uphill_ = 0;
};

}  // namespace esif
