#include "run/RunFiles.h"

#include <esif/core/Errors.h>
#include <esif/eval/LandmarkIdentities.h>
#include <esif/eval/LocalMapEvaluation.h>
#include <esif/eval/ReferenceResultDifference.h>
#include <esif/formats/AssociationFile.h>
#include <esif/formats/LocalMapFiles.h>
#include <esif/localmaps/LocalMapReplay.h>
#include <esif/localmaps/LocalMapRunPipeline.h>
#include <esif/run/RunConfig.h>
#include <esif/run/RunStats.h>

#include <chrono>
#include <filesystem>

namespace esif
{
namespace
{
/// What every local-map run writes, checked before the folder is put in place
/// (landmarks.gz too, unless the map is too wide for it: MapOutputs.cpp).
const std::vector<std::string> kLocalMapRunOutputFiles = {
	"landmarks.txt", "trajectory.tum", "map.simplemap", "scene.3Dscene", "map.png", "map.svg",
	"localmap_times.png", "localmap_times.svg", "params.ini", kAssociationFileName,
	kLandmarkIdentityFileName, "stats.json"};

/// What the run was given, read before any output is written.
struct LocalMapInput
{
	LocalMapFolder folder;
	std::optional<ReferenceResult> reference;
	std::size_t steps = 0;	///< the maps' steps (0 when read from files)
	std::size_t feature_entries = 0;
};

LocalMapInput readInput(const LocalMapRunRequest& request)
{
	LocalMapInput in;
	in.folder = readLocalMapFolder(request.local_maps_dir);
	if (request.reference_result_dir)
		in.reference = readReferenceResult(*request.reference_result_dir, in.folder.maps.size());
	for (const auto& map : in.folder.maps)
	{
		in.steps += map.steps;
		in.feature_entries += map.features.size();
	}
	return in;
}

/// The host settings that only apply to rawlogs are refused rather than ignored.
void rejectRawlogOnlyKeys(const ConfigFile& cfg, const HostParams& host)
{
	if (!host.associations_from.empty())
		throw ConfigError(cfg.section(kHostSection)
							  .describeKey("associations_from", "applies to rawlog input only, not to --local-maps"));
	if (!host.initial_run.empty())
		throw ConfigError(
			cfg.section(kHostSection).describeKey("initial_run", "applies to rawlog input only, not to --local-maps"));
}

Stats collectStats(
	const HostParams& host, const LocalMapRunRequest& request, const LocalMapInput& in,
	const LocalMapReplayResult& result, const FilterPlugin& plugin, const MapScores& scores,
	const std::optional<Accuracy>& accuracy, const std::optional<ReferenceResultDifference>& difference,
	double total_wall_s)
{
	Stats s;
	const auto cost = plugin.costFigures();
	setRunIdentityStats(s, host, plugin, request.config_path);
	s.set("local_map_folder", StatValue(request.local_maps_dir));
	s.set("local_maps", StatValue(static_cast<long long>(in.folder.maps.size())));
	s.set("steps", StatValue(static_cast<long long>(in.steps)));
	s.set("measurements", StatValue(static_cast<long long>(in.feature_entries)));
	s.set("landmarks", StatValue(static_cast<long long>(result.record.final_estimate.landmarks.size())));
	s.set("wall_s", StatValue(result.wall_s));
	s.set("total_wall_s", StatValue(total_wall_s));
	setLocalMapJoinStats(s, in.folder.maps.size(), result.join_us, result.fusion_costs);
	setRunOutcomeStats(s, result.finish_us, cost, result.audit, scores, accuracy);
	if (difference) setReferenceResultStats(s, *difference);
	setPluginCounters(s, cost);
	return s;
}

/// The whole-state NEES against the folder's ground truth: its landmarks,
/// and the true end pose of map k for the state's pose of map k.
std::optional<StateNees> truthStateNees(
	const LocalMapFolder& folder, const FilterPlugin& plugin, const std::map<LandmarkId, LandmarkId>& filter_to_file,
	const std::string& what)
{
	if (!folder.truth_landmarks && !folder.truth_end_poses) return std::nullopt;
	StateReference reference;
	if (folder.truth_landmarks) reference.landmarks = *folder.truth_landmarks;
	if (folder.truth_end_poses) reference.poses_by_local_map = *folder.truth_end_poses;
	return finalStateNees(plugin, reference, filter_to_file, what);
}
}  // namespace

namespace
{
/// The whole run, writing into request.out_dir (the partial folder).
Stats runInto(const LocalMapRunRequest& request, PluginLoader& loader)
{
	const auto t0 = std::chrono::steady_clock::now();
	PhaseTimes times;
	const ConfigFile cfg = ConfigFile::load(request.config_path);
	const HostParams host = loadHostParams(cfg);
	rejectRawlogOnlyKeys(cfg, host);
	auto plugin = createConfiguredPlugin(cfg, host, loader);
	requireLocalMapJoiner(*plugin, cfg.origin(), host.plugin);
	const LocalMapInput in = times.time("read", [&] { return readInput(request); });

	LocalMapReplayResult result = replayLocalMaps(
		*plugin, in.folder.maps, request.local_maps_dir, {host.hide_landmark_ids, request.progress_bar});
	result.record.truth = localMapGroundTruth(in.folder);
	const auto filter_to_file = result.audit.filterToTrue();
	const LandmarkIdentities identities = landmarkIdentities(result.audit, result.record.final_estimate.landmarks);
	// No OSPA: local-map files hold information matrices, not the
	// measurement covariances the cut-off is taken from (MapOspa.h).
	const MapScores scores{scoreAssociations(identities, result.audit), std::nullopt, std::nullopt};
	const auto accuracy = times.time("evaluate", [&] {
		return evaluateLocalMapRun(in.folder, result.record.trajectory, result.record.final_estimate, filter_to_file);
	});
	std::optional<ReferenceResultDifference> difference;
	if (in.reference)
		difference = times.time("evaluate", [&] {
			return referenceResultDifference(
				result.record.final_estimate, result.record.trajectory, filter_to_file, *in.reference);
		});

	// fusion_costs holds one entry per map at least (LocalMapReplay.h), so
	// localmap_times.png is always written.
	writeRunFiles(
		request.out_dir, host, *plugin,
		{result.record, result.reports, result.fusion_costs, request.local_maps_dir, identities}, times);
	const double total_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	Stats stats = collectStats(host, request, in, result, *plugin, scores, accuracy, difference, total_wall_s);
	const auto nees =
		times.time("state_nees", [&] { return truthStateNees(in.folder, *plugin, filter_to_file, request.config_path); });
	closeRunStats(stats, nees, "truth", times, request.out_dir);
	return stats;
}
}  // namespace

Stats runLocalMapPipeline(const LocalMapRunRequest& request, PluginLoader& loader)
{
	return runInStagedFolder(
		request,
		{{"the config", request.config_path},
		 {"the local-map folder", request.local_maps_dir},
		 {"the reference result", request.reference_result_dir.value_or("")}},
		kLocalMapRunOutputFiles, [&](const LocalMapRunRequest& staged) { return runInto(staged, loader); });
}

}  // namespace esif
