#pragma once
/// \file RunPipeline.h
/// One `esif run`: config -> plugin -> rawlog replay -> evaluation -> outputs.

#include <esif/io/StatsJson.h>
#include <esif/plugin/PluginLoader.h>

#include <optional>
#include <string>

namespace esif
{
struct RunRequest
{
	std::string config_path;
	std::string rawlog_path;
	/// Ground-truth prefix; when empty, PREFIX is looked for beside the rawlog.
	std::optional<std::string> ground_truth_prefix;
	std::string out_dir;
	bool progress_bar = true;
};

/// Runs the whole pipeline and writes every output into request.out_dir:
/// map.simplemap, landmarks.gz, landmarks.txt, trajectory.tum, scene.3Dscene,
/// map.png, stats.json and params.ini (the effective parameters). Returns
/// the stats. Warnings (e.g. a truncated rawlog) go to stderr.
Stats runPipeline(const RunRequest& request, PluginLoader& loader);

}  // namespace esif
