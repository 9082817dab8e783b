#include "CommandLine.h"
#include "Commands.h"

#include <esif/core/Errors.h>
#include <esif/formats/StatsJson.h>
#include <esif/localmaps/LocalMapRunPipeline.h>
#include <esif/run/RunPipeline.h>

#include <iostream>

namespace esif::app
{
namespace
{
/// The input options that make sense together: one of --rawlog and
/// --local-maps, and the options of the other kind of input left out.
void checkInputOptions(
	const TCLAP::ValueArg<std::string>& rawlog, const TCLAP::ValueArg<std::string>& local_maps,
	const std::vector<const TCLAP::ValueArg<std::string>*>& rawlog_only,
	const TCLAP::ValueArg<std::string>& reference_result)
{
	if (rawlog.isSet() == local_maps.isSet())
		throw ConfigError("esif run: give exactly one of --rawlog FILE and --local-maps DIR (see --help)");
	if (local_maps.isSet())
		for (const auto* arg : rawlog_only)
			if (arg->isSet())
				throw ConfigError("esif run: --" + arg->getName() + " applies to --rawlog input, not to --local-maps");
	if (rawlog.isSet() && reference_result.isSet())
		throw ConfigError("esif run: --reference-result applies to --local-maps input, not to --rawlog");
}

void printSummary(const Stats& stats, const std::string& input, const std::string& out_dir, bool local_maps)
{
	std::cout << "esif run: " << statText(*stats.get("label")) << " on " << input << " -> " << out_dir << "\n";
	std::vector<std::string> keys = {"steps", "landmarks", "wall_s", "step_us_p50", "step_us_p99", "state_dim",
									 "da_wrong", "landmark_rmse_m", "ate_rmse_m", "landmark_consistent_fraction",
									 "state_nees", "state_nees_dof", "state_nees_consistent"};
	if (local_maps)
		keys = {"local_maps", "landmarks", "wall_s", "join_us_p50", "join_us_max", "state_dim", "da_wrong",
				"landmark_rmse_m", "ate_rmse_m", "landmark_consistent_fraction", "refres_landmark_rms_m",
				"refres_pose_rms_m", "state_nees", "state_nees_dof", "state_nees_consistent"};
	for (const auto& key : keys)
		if (!local_maps || stats.get(key)) std::cout << "  " << key << " = " << statText(stats.get(key).value_or(nullptr)) << "\n";
}
}  // namespace

int runCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd("Replays a rawlog, or a folder of local maps, through the plugin named in the config and "
					   "writes maps and stats.",
					   ' ', ESIF_VERSION);
	TCLAP::ValueArg<std::string> config("c", "config", "INI file: [esif] plugin = ClassName, plus the plugin's section",
										true, "", "FILE", cmd);
	TCLAP::ValueArg<std::string> rawlog("r", "rawlog", "MRPT rawlog (gz or plain); or give --local-maps", false, "",
										"FILE", cmd);
	TCLAP::ValueArg<std::string> local_maps(
		"", "local-maps",
		"folder of local maps (localmap_1.txt ..., the authors' format; ground truth beside them) for a local-map "
		"joining plugin, instead of --rawlog. Outputs as for a rawlog, with the maps' end poses as the trajectory "
		"(time = map index k) and localmap_times.png",
		false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> reference_result(
		"", "reference-result",
		"with --local-maps: a joined result (feature.txt, pose.txt, e.g. the authors' Linear SLAM output) to "
		"measure the run against: refres_landmark_rms_m, refres_landmark_max_m, refres_landmarks_matched, "
		"refres_pose_rms_m, refres_pose_max_m, refres_heading_rms_deg (modulo 2 pi), refres_poses_matched",
		false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> ground_truth(
		"g", "ground-truth",
		"ground-truth prefix P (P_ground_truth.txt, P_ground_truth_robot_path.txt); default: beside the rawlog",
		false, "", "PREFIX", cmd);
	TCLAP::ValueArg<std::string> out("o", "out", "output folder", true, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> plugin_dir("", "plugin-dir", "extra folder to search for plugins", false, "", "DIR",
											cmd);
	TCLAP::ValueArg<std::string> associations_from(
		"", "associations-from",
		"run folder whose associations.txt gives every measurement's landmark ID (overrides [esif] "
		"associations_from; esif compare sets it for a config naming another's label)",
		false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> reference_run(
		"", "reference-run",
		"run folder of a smoother on the same rawlog (the full-SLAM optimum's) to compute the whole-state NEES "
		"against instead of the ground truth: stats.json state_nees*, landmarks paired through the true landmark "
		"each stands for, poses by step (a filter's trajectory.tum holds each pose as estimated at its time, not "
		"finally). The reference shares the run's error, so only a NEES above the interval is a finding. Also the "
		"run's difference from it, the ref_* keys of esif compare --reference",
		false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> reference_run_name(
		"", "reference-run-name",
		"with --reference-run: how stats.json names the reference (state_nees_reference); default: the folder as "
		"given (esif compare gives the folder the reference has once the comparison is in place)",
		false, "", "NAME", cmd);
	TCLAP::SwitchArg quiet("q", "quiet", "no progress bar and no summary", cmd);
	TCLAP::SwitchArg no_figures(
		"", "no-figures",
		"write the data files only: no map.png, step_times.png, ... nor their .svg (what esif montecarlo runs; "
		"rawlog runs)",
		cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;
	checkInputOptions(rawlog, local_maps, {&ground_truth, &associations_from, &reference_run}, reference_result);
	if (local_maps.isSet() && no_figures.getValue())
		throw ConfigError("esif run: --no-figures applies to --rawlog input, not to --local-maps");

	auto loader = PluginLoader::withExtraFolder(valueIfSet(plugin_dir));
	if (local_maps.isSet())
	{
		LocalMapRunRequest request;
		request.config_path = config.getValue();
		request.local_maps_dir = local_maps.getValue();
		request.out_dir = out.getValue();
		if (reference_result.isSet()) request.reference_result_dir = reference_result.getValue();
		request.progress_bar = !quiet.getValue();
		const Stats stats = runLocalMapPipeline(request, loader);
		if (!quiet.getValue()) printSummary(stats, request.local_maps_dir, request.out_dir, true);
		return 0;
	}
	RunRequest request;
	request.config_path = config.getValue();
	request.rawlog_path = rawlog.getValue();
	if (ground_truth.isSet()) request.ground_truth_prefix = ground_truth.getValue();
	request.out_dir = out.getValue();
	request.progress_bar = !quiet.getValue();
	if (associations_from.isSet()) request.associations_from = associations_from.getValue();
	if (reference_run.isSet()) request.reference_run = reference_run.getValue();
	if (reference_run_name.isSet())
	{
		if (!reference_run.isSet()) throw ConfigError("esif run: --reference-run-name applies with --reference-run only");
		request.reference_run_name = reference_run_name.getValue();
	}
	request.figures = !no_figures.getValue();
	const Stats stats = runPipeline(request, loader);
	if (!quiet.getValue()) printSummary(stats, request.rawlog_path, request.out_dir, false);
	return 0;
}

}  // namespace esif::app
