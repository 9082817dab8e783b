#include <esif/core/Elapsed.h>
#include <esif/core/Errors.h>
#include <esif/io/ProgressBar.h>
#include <esif/run/LocalMapReplay.h>

#include <chrono>
#include <new>
#include <stdexcept>

namespace esif
{
namespace
{
using Clock = SteadyClock;

/// Out of memory in a plugin: a numerical failure (exit code 3), as in
/// replay() (Replay.cpp says why). The joiner's landmark count is not at
/// hand, its state dimension (costFigures(), before the failing map) is.
NumericalError outOfMemory(
	const std::string& origin, const std::string& when, const std::string& plugin, std::size_t state_dim)
{
	return NumericalError(
		origin + ": out of memory " + when + " in plugin " + plugin + " (state of dimension " +
		std::to_string(state_dim) + ")");
}

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

	ProgressBar progress(out.record.plugin, options.progress_bar ? shown.size() : 0);
	std::vector<std::size_t> state_dims;
	const auto t_start = Clock::now();
	for (std::size_t i = 0; i < shown.size(); ++i)
	{
		const auto t0 = Clock::now();
		try
		{
			joiner->joinLocalMap(shown[i]);
		}
		catch (const NumericalError& e)
		{
			throw NumericalError(origin + ": local map " + std::to_string(shown[i].index) + ": " + e.what());
		}
		catch (const std::bad_alloc&)
		{
			throw outOfMemory(
				origin, "at local map " + std::to_string(shown[i].index), out.record.plugin,
				state_dims.empty() ? 0 : state_dims.back());
		}
		out.join_us.push_back(microsecondsSince(t0));
		// Outside the timed part: only needed when the plugin reports no costs.
		state_dims.push_back(plugin.costFigures().state_dim);
		progress.update(i + 1);
	}
	const auto t_finish = Clock::now();
	try
	{
		plugin.finish();
	}
	catch (const std::bad_alloc&)
	{
		throw outOfMemory(origin, "after the last local map", out.record.plugin, state_dims.empty() ? 0 : state_dims.back());
	}
	out.finish_us = microsecondsSince(t_finish);
	out.wall_s = microsecondsSince(t_start) * 1e-6;
	progress.finish();

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
