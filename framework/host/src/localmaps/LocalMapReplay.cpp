#include "run/ReplayLoop.h"

#include <esif/core/Errors.h>
#include <esif/localmaps/LocalMapReplay.h>

#include <stdexcept>

namespace esif
{
namespace
{
/// The files' feature IDs of one map: the truth its report is scored against.
std::vector<std::optional<LandmarkId>> fileIdsOf(const LocalMap& map)
{
	std::vector<std::optional<LandmarkId>> ids;
	ids.reserve(map.features.size());
	for (const auto& f : map.features) ids.emplace_back(f.id);
	return ids;
}

/// Each map's report, checked against its feature count and audited.
void collectReports(const LocalMapJoiner& joiner, const std::vector<LocalMap>& maps, LocalMapReplayResult& out)
{
	for (const LocalMap& map : maps)
	{
		StepReport report = joiner.mapReport(map.index);
		if (report.associations.size() != map.features.size())
			throw std::logic_error(
				"plugin " + out.record.plugin + " reported " + std::to_string(report.associations.size()) +
				" associations for the " + std::to_string(map.features.size()) + " features of local map " +
				std::to_string(map.index));
		out.audit.record(report, fileIdsOf(map));
		out.reports.push_back(std::move(report));
	}
}

/// The end poses as the record's trajectory (step = time = k) and as
/// keyframes with empty sensory frames, for map.simplemap.
void collectEndPoses(const LocalMapJoiner& joiner, std::size_t map_count, RunRecord& record)
{
	const std::vector<PoseEstimate> poses = joiner.endPoses();
	if (poses.size() != map_count)
		throw std::logic_error(
			"plugin " + record.plugin + " returned " + std::to_string(poses.size()) + " end poses for " +
			std::to_string(map_count) + " local maps");
	for (std::size_t i = 0; i < poses.size(); ++i)
	{
		record.trajectory.push_back({i + 1, static_cast<double>(i + 1), poses[i]});
		record.keyframes.push_back({poses[i], nullptr, i + 1});
	}
}
}  // namespace

std::vector<LocalMap> withHiddenFeatureIds(const std::vector<LocalMap>& maps)
{
	std::vector<LocalMap> out = maps;
	LandmarkId next = 1;
	for (LocalMap& map : out)
	{
		map.ids_identify_features = false;
		for (auto& f : map.features)
		{
			f.id = next++;
			f.in_earlier_maps = false;
		}
	}
	return out;
}

LocalMapReplayResult replayLocalMaps(
	FilterPlugin& plugin, const std::vector<LocalMap>& maps, const std::string& origin,
	const LocalMapReplayOptions& options)
{
	auto* joiner = dynamic_cast<LocalMapJoiner*>(&plugin);
	LocalMapReplayResult out;
	out.record.plugin = plugin.GetRuntimeClass()->className;
	if (!joiner) throw std::invalid_argument("replayLocalMaps: plugin " + out.record.plugin + " is not a LocalMapJoiner");
	out.record.rawlog = origin;
	std::vector<LocalMap> hidden;
	if (options.hide_landmark_ids) hidden = withHiddenFeatureIds(maps);
	const std::vector<LocalMap>& shown = options.hide_landmark_ids ? hidden : maps;

	std::vector<std::size_t> state_dims;
	ReplaySource source;
	source.origin = origin;
	source.plugin = out.record.plugin;
	source.count = shown.size();
	source.input_name = "local map";
	source.input_number = [&](std::size_t i) { return shown[i].index; };
	source.feed = [&](std::size_t i) { joiner->joinLocalMap(shown[i]); };
	// Outside the timed part: only needed when the plugin reports no costs.
	source.after = [&](std::size_t) { state_dims.push_back(plugin.costFigures().state_dim); };
	// The joiner's landmark count is not at hand, its state dimension (before the failing map) is.
	source.state = [&] { return "dimension " + std::to_string(state_dims.empty() ? 0 : state_dims.back()); };
	ReplayTimes times = runReplayLoop(plugin, source, options.progress_bar);
	out.join_us = std::move(times.feed_us);
	out.finish_us = times.finish_us;
	out.wall_s = times.wall_s;

	collectReports(*joiner, maps, out);
	collectEndPoses(*joiner, maps.size(), out.record);
	out.record.final_estimate = plugin.estimate();
	out.fusion_costs = joiner->fusionCosts();
	if (out.fusion_costs.empty())
		for (std::size_t i = 0; i < maps.size(); ++i)
			out.fusion_costs.push_back({maps[i].index, out.join_us[i] * 1e-6, 0.0, state_dims[i]});
	return out;
}

}  // namespace esif
