#pragma once
/// \file DeadReckoningJoiner.h
/// A small but real map-joining plugin for host tests (never installed in
/// the host's plugin folder; the tests load it with --plugin-dir). It places
/// each local map by composing the end poses (start(k) = end(k-1), or that
/// pose composed with the map's link odometry), moves the features into the
/// global frame and averages the positions of repeated landmarks;
/// covariances by first-order propagation (the map's own and its start
/// pose's, taken as independent), a repeated landmark keeping the mean of
/// its covariances (conservative: the copies share the start-pose error).
///
/// Association: by the maps' feature IDs, or, with match_distance_m > 0,
/// each feature to the nearest global landmark within that distance not yet
/// matched in the same map (else a new landmark, numbered by the plugin):
/// the mode for hidden IDs. Fed with steps, it builds its own local maps
/// with the framework's LocalMapBuilder and settles every step's report
/// when the step's map is fused (finalReports()).

#include <esif/localmap/LocalMapBuilder.h>
#include <esif/plugin/FilterPlugin.h>
#include <esif/plugin/LocalMapJoiner.h>

#include <map>
#include <optional>
#include <set>
#include <vector>

namespace esif::test
{
struct DeadReckoningJoinerParams
{
	LocalMapBuilderParams builder;
	double match_distance_m = 0;  ///< 0: associate by ID; > 0: nearest global landmark within this distance

	void declare(ParamBinder& b);
};

class DeadReckoningJoiner : public FilterPlugin, public LocalMapJoiner
{
	DEFINE_MRPT_OBJECT(DeadReckoningJoiner, esif::test)

   public:
	// FilterPlugin
	std::string sectionName() const override { return "dead_reckoning_joiner"; }
	void configure(const ConfigSection& section) override;
	std::vector<ParamInfo> parameters() const override { return describeParams(params_); }
	StepReport processStep(const StepInput& step) override;
	void finish() override;
	PoseEstimate robotPose() const override;
	Estimate estimate() const override;
	CostFigures costFigures() const override;
	std::optional<std::vector<StepReport>> finalReports() const override;

	// LocalMapJoiner
	LocalMapBuilderParams localMapBuilderParams() const override { return params_.builder; }
	void joinLocalMap(const LocalMap& map) override;
	std::vector<PoseEstimate> endPoses() const override { return end_poses_; }
	StepReport mapReport(std::size_t k) const override;
	std::vector<LocalMapFusionCost> fusionCosts() const override { return costs_; }

	/// The IDs of every feature the plugin was given, map by map (for tests).
	const std::vector<std::vector<LandmarkId>>& idsSeen() const { return ids_seen_; }

   private:
	/// A global landmark: the sums of its copies' positions and covariances.
	struct Landmark
	{
		Eigen::Vector2d position_sum = Eigen::Vector2d::Zero();
		Eigen::Matrix2d covariance_sum = Eigen::Matrix2d::Zero();
		std::size_t copies = 0;
	};
	/// A feature of the map being fused, in the global frame.
	struct PlacedFeature
	{
		Eigen::Vector2d position;
		Eigen::Matrix2d covariance;
	};

	PoseEstimate startPoseOf(const LocalMap& map) const;
	std::vector<PlacedFeature> placeFeatures(const LocalMap& map, const PoseEstimate& start) const;
	StepReport associate(const LocalMap& map, const std::vector<PlacedFeature>& placed);
	void settleStepReports(const LocalMap& map, const StepReport& report);

	DeadReckoningJoinerParams params_;
	std::optional<LocalMapBuilder> builder_;  ///< on rawlog input
	std::size_t steps_ = 0;
	std::map<LandmarkId, Landmark> landmarks_;
	LandmarkId next_own_id_ = 1;  ///< landmarks numbered by the plugin (match_distance_m > 0)
	std::vector<PoseEstimate> end_poses_;
	std::vector<StepReport> map_reports_;
	std::vector<LocalMapFusionCost> costs_;
	std::vector<std::vector<LandmarkId>> ids_seen_;
	std::vector<StepReport> final_reports_;
	std::set<LandmarkId> settled_ids_;
	bool finished_ = false;
};

}  // namespace esif::test
