#pragma once
/// \file LocalMapReplay.h
/// The replay loop on local-map input (`esif run --local-maps DIR`): feeds
/// the maps of a folder, in order, to a map-joining plugin
/// (LocalMapJoiner), times each fusion, and collects the estimate, the end
/// poses, each map's association report and the plugin's fusion costs.
///
/// Landmark IDs: the files' feature IDs are the data association of the
/// authors' maps. With `hide_landmark_ids` the plugin is shown every feature
/// of every map under a number of its own (unique per map entry), so it must
/// associate by itself; its decisions are still scored against the files'
/// IDs, exactly as hidden rawlog IDs are.

#include <esif/eval/AssociationAudit.h>
#include <esif/formats/RunRecord.h>
#include <esif/localmap/LocalMap.h>
#include <esif/plugin/FilterPlugin.h>
#include <esif/plugin/LocalMapJoiner.h>

#include <string>
#include <vector>

namespace esif
{
struct LocalMapReplayOptions
{
	bool hide_landmark_ids = false;	 ///< renumber the features the plugin sees (see above)
	bool progress_bar = true;  ///< shown only when stderr is a terminal
};

struct LocalMapReplayResult
{
	/// trajectory: the global end pose of every map (step = time_s = k, from
	/// 1); keyframes: the same poses with empty sensory frames (for
	/// map.simplemap); final_estimate: the plugin's after finish();
	/// rawlog: the folder read.
	RunRecord record;
	std::vector<double> join_us;  ///< joinLocalMap() time of each map [us] (index k-1)
	double finish_us = 0;  ///< time of finish() [us]
	double wall_s = 0;	///< every fusion and finish() [s]
	/// The plugin's mapReport(k) of each map (index k-1), after finish(),
	/// for associations.txt ("step" k, "measurement" = feature index).
	std::vector<StepReport> reports;
	/// The plugin's fusionCosts() after finish(); when it reports none, one
	/// per map from the host's timing (no association split) and the plugin's
	/// state dimension after each fusion.
	std::vector<LocalMapFusionCost> fusion_costs;
	/// The reports scored against the files' feature IDs.
	AssociationAudit audit;
};

/// The maps as the plugin sees them with hidden IDs: every feature entry
/// numbered 1, 2, ... in map order (no two alike, whatever the files say),
/// ids_identify_features false, and no feature flagged as in_earlier_maps
/// (the flag is knowledge of the IDs).
std::vector<LocalMap> withHiddenFeatureIds(const std::vector<LocalMap>& maps);

/// Runs the joining plugin over `maps` (k = 1, 2, ... in order; `origin`
/// names the folder in messages). `plugin` must be a LocalMapJoiner (else
/// std::invalid_argument: the caller checks it with a user-facing message).
/// A NumericalError is rethrown with the folder and map prefixed. A report
/// whose size is not the map's feature count, or end poses not one per map,
/// throw std::logic_error naming the plugin (a plugin bug, not bad input).
LocalMapReplayResult replayLocalMaps(
	FilterPlugin& plugin, const std::vector<LocalMap>& maps, const std::string& origin,
	const LocalMapReplayOptions& options);

}  // namespace esif
