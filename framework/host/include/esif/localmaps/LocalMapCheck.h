#pragma once
/// \file LocalMapCheck.h
/// `esif localmaps check`: where a map-joining run becomes over-confident.
/// The local maps the config's joining plugin would fuse are built from the
/// rawlog (as `esif localmaps build` does: the authors' file format carries
/// no step ranges, and a map's start and end must be placed on the
/// reference path by step), then
///  - each local map is held against the reference in its start frame
///    (eval/LocalMapConsistency.h): the NEES of the whole map, of its end
///    pose, and the share of its features inside their own 95% ellipse;
///  - the maps are fused one by one by a fresh instance of the plugin, and
///    after each fusion the whole state is held against the reference
///    (eval/StateNees.h).
/// If the local maps are consistent and the joined state is not, the fusion
/// is at fault. The reference is the rawlog's ground truth or, where there
/// is none (real data), another run on the same rawlog (the full-SLAM
/// optimum): its landmarks by the rawlog's IDs and its trajectory by step.
///
/// Writes local_maps_nees.csv, fusion_nees.csv and consistency.png (NEES per
/// degree of freedom of both, with the 95% bands) into one all-or-nothing
/// output folder.

#include <esif/eval/LocalMapConsistency.h>
#include <esif/loader/PluginLoader.h>

#include <optional>
#include <string>
#include <vector>

namespace esif
{
struct LocalMapCheckRequest
{
	std::string config_path;  ///< `[esif] plugin` must be a local-map joining plugin
	std::string rawlog_path;
	std::optional<std::string> ground_truth_prefix;	 ///< default: beside the rawlog
	std::optional<std::string> reference_run;  ///< instead of the ground truth
	std::string out_dir;
	int image_size_px = 1200;
	bool progress_bar = true;
};

/// The whole state after fusing map k.
struct FusionConsistency
{
	std::size_t index = 0;	///< k
	StateNees nees;
};

struct LocalMapCheckResult
{
	std::string reference;	///< "truth" or the reference run folder
	std::vector<LocalMapConsistency> maps;
	std::vector<FusionConsistency> fusions;	 ///< empty when the plugin reports no state information
};

/// The whole command. Throws ConfigError when there is neither a ground
/// truth nor --reference-run, InputError when the reference run's
/// trajectory does not have one row per rawlog step.
LocalMapCheckResult runLocalMapCheck(const LocalMapCheckRequest& request, PluginLoader& loader);

/// The two CSV files' text (one row per map / per fusion).
std::string localMapNeesCsv(const std::vector<LocalMapConsistency>& maps);
std::string fusionNeesCsv(const std::vector<FusionConsistency>& fusions);

}  // namespace esif
