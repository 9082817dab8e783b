#pragma once
/// \file Dslam.h
/// D-SLAM (book Ch. 3): decoupled localisation and mapping. Each scan is
/// recast into z_map (distances and angles among features) and z_rob
/// (Sec. 3.1.1). Mapping is a static EIF over feature positions only, with
/// an exactly sparse information matrix (Sec. 3.1.3, 3.2). Localisation
/// (Sec. 3.1.4, Fig. 3.4) fuses, by covariance intersection, a local EKF
/// SLAM over the features in view with the "kidnapped robot" pose from the
/// map. Scans seeing fewer than two mapped features are combined into
/// admissible virtual observations (Sec. 3.4.1); without landmark IDs,
/// associations are verified on relative distances and angles (Sec. 3.4.2).
///
/// One step, in the order of Fig. 3.4: predict (A-B); associate; local
/// SLAM observe (B-C); kidnapped robot from Map(k) (F-G); CI (C, G -> D);
/// new features into the local SLAM (E); map update to Map(k+1); recovery.
///
/// Beyond the book: measurements failing a chi-square gate against the local
/// SLAM or, jointly on z_map, against the map are rejected whatever the
/// association (OutlierGate.h); a diverging map stops the run
/// (DivergenceGuard.h); the map updates share one linearisation point per
/// feature, and every relinearise_every_steps steps, or at once after a
/// large correction, those whose features moved are evaluated again at the
/// current estimate; the kidnapped-robot solution is iterated; the local
/// SLAM may hold features out of view, which then anchor the relative tests
/// of lone sightings without IDs (DslamParams.h says why).

#include "AdmissibleChain.h"
#include "DivergenceGuard.h"
#include "DslamParams.h"
#include "HeldFeatureTracking.h"
#include "KidnappedRobot.h"
#include "LocalSlam.h"

#include <esif/association/TentativeFeatures.h>
#include <esif/plugin/PluginWithParams.h>
#include <esif/relative/FeatureMap.h>
#include <esif/relative/RelativeAssociation.h>

#include <memory>
#include <optional>
#include <unordered_set>

namespace esif
{
class Dslam : public PluginWithParams<dslam::DslamParams>
{
	DEFINE_MRPT_OBJECT(Dslam, esif)

   public:
	std::string sectionName() const override { return "dslam"; }
	StepReport processStep(const StepInput& step) override;
	void finish() override;
	/// New features without a measured ID are numbered above the input's IDs.
	void reserveLandmarkIds(LandmarkId largest_input_id) override;
	PoseEstimate robotPose() const override;
	Estimate estimate() const override;
	CostFigures costFigures() const override;
	Formulation formulation() const override { return Formulation::Dslam; }
	std::optional<InformationPattern> informationPattern() const override;
	std::optional<StateInformation> stateInformation() const override;

   private:
	void start() override;
	/// A scan's associated measurements and what they say about admissibility.
	struct Observed
	{
		std::vector<dslam::IdentifiedMeasurement> all;	 ///< matched and new, scan order
		relative::PointSet points;						 ///< `all` in the robot frame (T1)
		std::vector<int> mapped;						 ///< indices into `all` of features in Map(k)
		std::optional<std::pair<int, int>> pair;		 ///< reference pair (indices into `all`)
	};

	StepReport associateScan(const StepInput& step);
	StepReport associateByIds(const StepInput& step) const;
	StepReport associateByTrackingThenMap(const Scan& scan);
	/// Adds the mapped features the local SLAM holds out of view to the
	/// anchors of the map-level association's relative tests.
	void addHeldAnchors(const Scan& scan, const std::vector<dslam::TrackedMeasurement>& tracked,
						std::vector<relative::RelativeAssociation::Anchor>& anchors) const;
	void nameNewFeatures(StepReport& report);
	void holdFirstSightings(const StepInput& step, StepReport& report);
	void rejectOutliers(const Scan& scan, StepReport& report);
	void rejectReobservationOutliers(const Scan& scan, StepReport& report);
	/// Up to `passes` relinearisations of the map updates, each followed by
	/// a recovery; stops when no update moved.
	void relinearise(int passes);
	/// The map update and recovery of this scan, relinearised at once when
	/// they changed the relative geometry of the scan's mapped features by
	/// more than relinearise_on_correction_m.
	void updateAndRecoverMap(const Observed& obs, const Pose2& sensor);
	Observed observed(const Scan& scan, const StepReport& report) const;
	void localize(const Observed& obs, const Pose2& sensor);
	void fuseWithKidnappedRobot(const Observed& obs, const Pose2& sensor);
	/// After relocalise_after_disagreeing_scans disagreements in a row,
	/// whether the map's estimate fits its scan well enough to replace the
	/// local SLAM (DslamParams.h).
	bool relocalisationDue(const dslam::KidnappedInput& in, const dslam::GaussianState& from_map) const;
	bool robotEstimatesAgree(const dslam::GaussianState& local, const dslam::GaussianState& from_map) const;
	void updateMap(const Observed& obs, const Pose2& sensor);
	void applyVirtualObservation(const Pose2& sensor);
	relative::MapUpdate updateFromPair(const std::vector<LandmarkId>& ids, const relative::PointSet& points,
									   std::pair<int, int> pair);

	std::unique_ptr<relative::FeatureMap> map_;	 // mutable state behind a const
												 // estimate(): recovery caches
	std::unique_ptr<relative::RelativeAssociation> association_;
	dslam::LocalSlam local_;
	dslam::AdmissibleChain chain_;
	dslam::DivergenceGuard guard_;
	std::optional<TentativeFeatures> confirmation_;
	std::optional<relative::MapUpdate> pending_;  ///< last map update, withdrawn if the next scan is inadmissible
	std::unordered_set<LandmarkId> started_;	  ///< features reported New so far
	LandmarkId next_own_id_ = 0;
	int steps_since_relinearisation_ = 0;
	bool associated_by_ids_ = false;  ///< this scan's associations come from landmark IDs

	struct Tally
	{
		std::size_t admissible = 0, inadmissible = 0, withdrawals = 0, virtual_updates = 0,
					anchor_updates = 0, ci_fusions = 0, ci_failures = 0, local_gate_rejections = 0,
					map_gate_rejections = 0, reobservation_gate_rejections = 0, unconfirmed_sightings = 0, tracked_matches = 0,
					ci_disagreements = 0,
					relinearisations = 0;
		double omega_sum = 0;
		std::size_t relinearised_terms = 0;
		std::size_t corrections_relinearised = 0;  ///< relinearisations triggered by a large correction
		std::size_t relocalisations = 0;
	} tally_;
};

}  // namespace esif
