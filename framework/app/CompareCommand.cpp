#include "CommandLine.h"
#include "Commands.h"
#include "PluginPreload.h"

#include <esif/compare/Comparison.h>
#include <esif/core/Errors.h>
#include <esif/core/Text.h>
#include <esif/safeio/RunServer.h>

#include <iostream>

namespace esif::app
{
int compareCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd("Runs several configs on one rawlog (or folder of local maps), each in its own process, and "
					   "tabulates them. Every config and its plugin is checked before the first run. A run that "
					   "fails is a row with status 'failed', its exit code and its first error line, the others "
					   "still run, the tables are written all the same, and compare exits with the code of the "
					   "first failed run in --configs order (0 when none failed).",
					   ' ',
					   ESIF_VERSION);
	TCLAP::ValueArg<std::string> configs("c", "configs", "comma-separated INI files", true, "", "A.ini,B.ini,...", cmd);
	TCLAP::ValueArg<std::string> rawlog("r", "rawlog", "MRPT rawlog (gz or plain); or give --local-maps", false, "",
										"FILE", cmd);
	TCLAP::ValueArg<std::string> local_maps(
		"", "local-maps",
		"folder of local maps (localmap_k.txt, ground truth beside them) instead of --rawlog; every config must "
		"name a local-map joining plugin",
		false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> reference_result(
		"", "reference-result",
		"with --local-maps: a joined result (feature.txt, pose.txt) every run is measured against (refres_* keys)",
		false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> ground_truth("g", "ground-truth", "ground-truth prefix; default: beside the rawlog",
											  false, "", "PREFIX", cmd);
	TCLAP::ValueArg<std::string> out("o", "out", "output folder (one subfolder per config)", true, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> plugin_dir("", "plugin-dir", "extra folder to search for plugins", false, "", "DIR",
											cmd);
	TCLAP::ValueArg<std::string> reference(
		"", "reference",
		"label of the run the others are compared with (for data without ground truth), or a run folder outside "
		"the comparison holding trajectory.tum and landmarks.txt (e.g. another solver's solution read by esif "
		"import g2o): adds each run's "
		"difference from it, in the shared initial-pose frame without alignment, as ref_traj_rms_m, "
		"ref_traj_max_m, ref_heading_rms_deg (poses of the same step), ref_landmark_rms_m, ref_landmark_max_m "
		"and ref_landmarks_matched (landmarks paired through the true landmark each stands for, or, where a run "
		"has none, by the optimal assignment within its OSPA cut-off: ref_landmarks_paired_by), ref_ospa_m. "
		"The reference's row shows zeros and its own landmark count. On a rawlog every other run also computes its "
		"whole-state NEES against the reference (state_nees*, as esif run --reference-run). Default without "
		"ground truth: the "
		"optimization baseline (the full-SLAM run), if any",
		false, "", "LABEL|DIR", cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;
	// Each config's run is a fork of the run server (RunServer.h), started
	// before this process opens a file or starts a thread, with the plugins
	// already loaded (PluginPreload.h).
	preloadPlugins(valueIfSet(plugin_dir));
	const RunServer server(runMain);
	if (rawlog.isSet() == local_maps.isSet())
		throw ConfigError("esif compare: give exactly one of --rawlog FILE and --local-maps DIR (see --help)");
	if (local_maps.isSet() && ground_truth.isSet())
		throw ConfigError("esif compare: --ground-truth applies to --rawlog input, not to --local-maps");
	if (rawlog.isSet() && reference_result.isSet())
		throw ConfigError("esif compare: --reference-result applies to --local-maps input, not to --rawlog");

	const Comparison comparison({splitCommas(configs.getValue()), rawlog.getValue(), local_maps.getValue(),
								 ground_truth.getValue(), reference_result.getValue(), reference.getValue(),
								 out.getValue(), valueIfSet(plugin_dir)});
	const auto [exit_code, text] = comparison.run();
	std::cout << text;	// once the folder is in place
	return exit_code;
}

}  // namespace esif::app
