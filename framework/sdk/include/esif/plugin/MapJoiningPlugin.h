#pragma once
/// \file MapJoiningPlugin.h
/// What every map-joining plugin (book Ch. 4-5) does on a rawlog, written
/// once: it owns the LocalMapBuilder, feeds it the steps, and hands each
/// closed local map to the plugin's fusion, exactly as a map read from a
/// local-map folder is handed to it (`esif run --local-maps`). A joining
/// plugin derives from this class and implements the fusion (fuseLocalMap,
/// finishJoining), the LocalMapJoiner queries and its own parameters.
///
/// Notes to implementers:
/// - Derive through PluginWithParams<Params, MapJoiningPlugin>, which starts
///   the builder with the parameters' `builder` member.
/// - fuseLocalMap() receives the maps in order (k = 1, 2, ...), from the
///   builder or from files; the file side is checked for order here first.
/// - Declare the class with DEFINE_MRPT_OBJECT and implement it with
///   IMPLEMENTS_MRPT_OBJECT(Name, FilterPlugin, esif), as any plugin.

#include <esif/localmap/LocalMapBuilder.h>
#include <esif/plugin/FilterPlugin.h>
#include <esif/plugin/LocalMapJoiner.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
class SparseInformationCore;

class MapJoiningPlugin : public FilterPlugin, public LocalMapJoiner
{
   public:
	/// Feeds the step to the open local map; a map the step closes is fused
	/// at once (fuseLocalMap).
	StepReport processStep(const StepInput& step) final;
	/// Checks that `map` is the next one (k = maps given so far + 1) and
	/// acceptable (checkGivenMap), then fuses it.
	void joinLocalMap(const LocalMap& map) final;
	/// Closes and fuses the open local map, then finishJoining().
	void finish() final;
	/// The local-map builder numbers its own features above the input's IDs.
	void reserveLandmarkIds(LandmarkId largest_input_id) final;
	/// Each step's measurements as finally settled by the fusion of its map:
	/// a local feature's provisional ID replaced by its global one.
	std::optional<std::vector<StepReport>> finalReports() const final;
	/// The global map's information matrix (book Fig. 4.12, 5.5).
	std::optional<InformationPattern> informationPattern() const final;
	LocalMapBuilderParams localMapBuilderParams() const final { return builder_params_; }

   protected:
	/// `filter_name` starts the error messages about given maps ("SLSJF").
	explicit MapJoiningPlugin(std::string filter_name) : filter_name_(std::move(filter_name)) {}

	/// Starts the local-map builder with the plugin's builder parameters
	/// (PluginWithParams::configure calls it).
	void startBuilder(const LocalMapBuilderParams& params);
	const LocalMapBuilder& builder() const;
	/// Appends the local maps' sighting rejections (local_ambiguous_waits,
	/// local_poorly_observed_sightings, local_unconfirmed_sightings) when
	/// this run builds its local maps; nothing when it joins given ones.
	void appendLocalMapCounters(std::vector<std::pair<std::string, double>>& counters) const;
	/// Whether any step so far had a measurement without a landmark ID.
	bool sawMeasurementWithoutId() const { return saw_measurement_without_id_; }
	/// Whether the local maps this run builds were associated scan by scan
	/// with the global map (local_map_global_features_radius_m): their
	/// features' IDs are then global IDs, which the map level checks by ID.
	bool localFeaturesCarryGlobalIds() const
	{
		return built_from_steps_ && builder_params_.local_map_global_features_radius_m > 0;
	}
	/// Every step's robot pose in its local map's frame (the end pose for the
	/// step that closed a map), in step order.
	const std::vector<PoseEstimate>& localPoses() const { return local_poses_; }

	/// One fusion's inputs and decisions, for finalReports().
	struct SettledFusion
	{
		const std::vector<StepReport>& step_reports;  ///< of the fused map's steps (empty for a file's map)
		const std::vector<LandmarkId>& feature_ids;	 ///< the fused map's feature IDs, in order
		const StepReport& decisions;  ///< one per feature: global id or rejected
	};

	/// Fuses local map `map` (maps arrive in order from 1).
	virtual void fuseLocalMap(const LocalMap& map) = 0;
	/// After the last map is fused: final relinearisation, covariances.
	virtual void finishJoining() = 0;
	/// Throws InputError for a map read from a file that this filter cannot fuse.
	virtual void checkGivenMap(const LocalMap& map) const {}
	/// The fusions so far, in order.
	virtual std::vector<SettledFusion> settledFusions() const = 0;
	/// The global map's information (for informationPattern()).
	virtual SparseInformationCore& globalInformation() const = 0;
	/// For the builder's close rule without IDs
	/// (LocalMapBuilder::countOwnFeaturesWith): how many of the open map's
	/// own features the global map holds; nullopt (the default) when the
	/// filter cannot tell.
	virtual std::optional<std::size_t> ownFeaturesInGlobalMap(
		const LandmarkEkf& open_map, const std::set<LandmarkId>& own_ids) const
	{
		return std::nullopt;
	}

	/// For local_map_global_features_radius_m: the global map's features
	/// within `radius_m` of the open map's start, in the open map's frame
	/// (earlierFeaturesInFrame), after a fusion. The open map's start is the
	/// last fused map's end pose (with local_map_link = odometry the builder
	/// moves them through the link). nullopt (the default): the filter
	/// cannot, and the first fusion stops with an InputError naming the key.
	virtual std::optional<EarlierFeatures> globalFeaturesNearOpenMapStart(double radius_m) { return std::nullopt; }

   private:
	void requireBuilder() const;
	/// After a fusion: the open map's earlier features (local_map_global_features_radius_m).
	void giveGlobalFeaturesToOpenMap();

	std::string filter_name_;
	LocalMapBuilderParams builder_params_;
	std::unique_ptr<LocalMapBuilder> builder_;
	std::size_t maps_given_ = 0;
	std::vector<PoseEstimate> local_poses_;
	bool saw_measurement_without_id_ = false;
	bool built_from_steps_ = false;
};

}  // namespace esif
