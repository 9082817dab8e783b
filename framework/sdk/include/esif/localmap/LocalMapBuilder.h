#pragma once
/// \file LocalMapBuilder.h
/// Builds the local maps of the map-joining filters (book Sec. 4.2.1, 4.6,
/// 5.1.1) from the host's steps: EKF SLAM (LandmarkEkf, the EKF plugin's
/// filter and association) from a start pose with zero uncertainty, closed
/// by the policy of LocalMapBuilderParams. The next map starts at the
/// closed map's end pose, so start(k+1) = end(k) exactly, or one step later
/// with that step's odometry as the link (eq. 5.4).
///
/// Landmark IDs: with the rawlog's IDs a feature keeps its ID in every map.
/// Without them the builder numbers new features itself (from 1, unique over
/// the whole log) and, when a map is closed, gives the features it matched
/// to the previous map (PreviousMapMatcher) that map's IDs, so that equal
/// IDs mean one feature in every map, as in the authors' files.
///
/// With local_map_global_features_radius_m > 0 the joining filter gives each
/// new map the global features near its start (setEarlierFeatures), and the
/// scans are associated by a second EKF, the association filter: the open
/// map's filter with those features added as landmarks, each with its
/// global estimate and their joint covariance in the map's frame. It
/// decides every measurement as the EKF plugin does (its waits, gates and
/// tentative features), and after a match it knows the robot better, so the
/// next sighting is judged against a corrected pose, as in the EKF. The
/// open map itself takes the decided measurements by ID and stays
/// independent of the global map (its information enters the global map
/// once, eq. 5.8): a feature first seen there as a global one carries its
/// global ID, and the close renames nothing (the scans have decided).

#include <esif/ekf/LandmarkEkf.h>
#include <esif/localmap/LocalMap.h>
#include <esif/localmap/LocalMapBuilderParams.h>

#include <functional>
#include <optional>
#include <set>
#include <vector>

namespace esif
{
class LocalMapBuilder
{
   public:
	explicit LocalMapBuilder(const LocalMapBuilderParams& params);

	/// Feeds one step into the open map (prediction, association, update,
	/// new features); returns its association report with the open map's
	/// IDs (provisional: a closed map's step_reports hold the final ones).
	/// When the close policy fires after this step, the map is closed and
	/// can be taken with takeClosedMap(). Throws NumericalError naming the
	/// map when the closed map's covariance is not positive definite.
	StepReport processStep(const StepInput& step);

	/// Numbers the features it numbers itself above `largest_input_id`, in
	/// the open map and every later one (FilterPlugin::reserveLandmarkIds).
	void reserveIdsUpTo(LandmarkId largest_input_id);

	/// Features of the global map in the open map's frame (EarlierFeatures.h),
	/// given after the previous map's fusion and before the open map's first
	/// step. With local_map_link = odometry they are moved through the link
	/// when it arrives.
	void setEarlierFeatures(EarlierFeatures features);
	/// Features of the local maps started under a global feature's ID, over every map so far.
	std::size_t earlierFeatureStarts() const { return earlier_starts_; }

	/// The map the last processStep() closed, if any (then cleared).
	std::optional<LocalMap> takeClosedMap();

	/// Closes the open map at the end of the log if it covers any step.
	std::optional<LocalMap> finish();

	/// The open map's filter: robot pose and features in the open map's frame.
	const LandmarkEkf& openMap() const { return ekf_; }
	/// Sightings the local maps' filters left out, by cause: every map so
	/// far, the open one included.
	SightingRejections rejections() const;
	/// Index k of the open map.
	std::size_t openMapIndex() const { return index_; }
	/// Steps the open map has taken in.
	std::size_t openMapSteps() const { return steps_; }
	/// The open map's link odometry (odometry link mode, after its first step).
	const std::optional<OdometryIncrement>& openMapLink() const { return link_; }

	/// Features of the open map known to be in the previous map, for the
	/// close rule (by ID, or matched geometrically when the builder numbered them).
	std::size_t openMapCommonFeatures() const;

	/// How many of the open map's own features (those the builder numbered:
	/// the input had no IDs) are features of the joining filter's global
	/// map; nullopt when the filter cannot tell.
	using OwnFeaturesInGlobalMap =
		std::function<std::optional<std::size_t>(const LandmarkEkf& open_map, const std::set<LandmarkId>& own_ids)>;
	/// With local_map_common_features_in = earlier_maps, the close rule
	/// counts own features with `counter` (as it counts features with IDs
	/// in any earlier map) instead of matching them to the previous map.
	void countOwnFeaturesWith(OwnFeaturesInGlobalMap counter) { own_in_global_ = std::move(counter); }

	/// The authors' stabilisation (their StabNoise): a robot variance below
	/// this is raised by it, so a map in which the robot did not move still
	/// has an information matrix. The closed map's covariance is the
	/// stabilised one: information = covariance^-1 for every map.
	static constexpr double kMinRobotVariance = 1e-6;

   private:
	/// A step with the association filter: it decides, the open map follows by ID.
	StepReport processAsTheGlobalMapDecides(const StepInput& step);
	void startAssociationFilter(const EarlierFeatures& features);
	bool policyWantsToClose() const;
	LocalMap closeOpenMap();
	std::vector<std::optional<std::size_t>> matchOwnFeaturesToPrevious() const;
	void startNextMap();

	LocalMapBuilderParams params_;
	LandmarkEkf ekf_;
	SightingRejections rejections_in_closed_maps_;
	std::size_t index_ = 1;
	std::size_t steps_ = 0, measurements_ = 0, first_step_ = 0, last_step_ = 0;
	double travelled_m_ = 0;
	bool link_pending_ = false;	 // odometry mode: the next step's odometry links the maps
	std::optional<OdometryIncrement> link_;
	std::set<LandmarkId> own_ids_;	// features of the open map numbered by the builder
	std::set<LandmarkId> earlier_ids_;	// IDs of the open map's earlier features
	std::optional<EarlierFeatures> earlier_through_link_;  // odometry link: set once the link is known
	std::optional<LandmarkEkf> association_ekf_;  // the open map's filter plus the earlier features
	std::size_t earlier_starts_ = 0;
	std::vector<StepReport> reports_;  // the open map's steps
	std::set<LandmarkId> ids_in_closed_maps_;
	std::optional<LocalMap> previous_;	// the last closed map
	OwnFeaturesInGlobalMap own_in_global_;
	std::optional<LocalMap> closed_;
	static constexpr LandmarkId kFirstOwnId = 1;  // features the builder numbers: 1, 2, ...
	LandmarkId next_own_id_ = kFirstOwnId;
};

}  // namespace esif
