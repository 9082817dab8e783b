#pragma once
/// \file LocalMapRunPipeline.h
/// One `esif run --local-maps DIR`: config -> map-joining plugin -> the
/// folder's local maps (LocalMapReplay.h) -> evaluation -> outputs.

#include <esif/formats/StatsJson.h>
#include <esif/plugin/LocalMapJoiner.h>
#include <esif/loader/PluginLoader.h>

#include <optional>
#include <string>

namespace esif
{
struct LocalMapRunRequest
{
	std::string config_path;
	std::string local_maps_dir;	 ///< localmap_1.txt ... and the ground truth beside them
	std::string out_dir;
	/// A joined result to measure the run against (feature.txt, pose.txt).
	std::optional<std::string> reference_result_dir;
	bool progress_bar = true;
};

/// Runs the whole pipeline and writes into request.out_dir what a rawlog
/// run writes, each atomically, with the end poses of the maps in place of
/// the trajectory: landmarks.gz, landmarks.txt, trajectory.tum (end pose k
/// at time k), map.simplemap (the end poses with empty sensory frames),
/// map.png and scene.3Dscene (the end poses as the path), associations.txt
/// ("step" = map k, "measurement" = feature index), info_matrix.png when the
/// plugin gives a pattern, localmap_times.png (Fig. 5.7-5.8), params.ini and
/// stats.json. Returns the stats. The folder is all-or-nothing, as a
/// rawlog run's (RunFolder.h).
///
/// Config errors (not a joining plugin, `[esif] associations_from` set,
/// which only applies to rawlogs), an unreadable folder or reference result
/// are found before any output is written. With the folder's ground truth
/// the accuracy keys are filled (LocalMapEvaluation.h); with a reference
/// result the refres_* keys (ReferenceResultDifference.h).
Stats runLocalMapPipeline(const LocalMapRunRequest& request, PluginLoader& loader);

}  // namespace esif
