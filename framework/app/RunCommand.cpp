#include "CommandLine.h"
#include "Commands.h"

#include <esif/io/StatsJson.h>
#include <esif/run/RunPipeline.h>

#include <iostream>

namespace esif::app
{
int runCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd("Replays a rawlog through the plugin named in the config and writes maps and stats.", ' ',
					   ESIF_VERSION);
	TCLAP::ValueArg<std::string> config("c", "config", "INI file: [esif] plugin = ClassName, plus the plugin's section",
										true, "", "FILE", cmd);
	TCLAP::ValueArg<std::string> rawlog("r", "rawlog", "MRPT rawlog (gz or plain)", true, "", "FILE", cmd);
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
	TCLAP::SwitchArg quiet("q", "quiet", "no progress bar and no summary", cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;

	RunRequest request;
	request.config_path = config.getValue();
	request.rawlog_path = rawlog.getValue();
	if (ground_truth.isSet()) request.ground_truth_prefix = ground_truth.getValue();
	request.out_dir = out.getValue();
	request.progress_bar = !quiet.getValue();
	if (associations_from.isSet()) request.associations_from = associations_from.getValue();
	PluginLoader loader(plugin_dir.isSet() ? std::vector<std::string>{plugin_dir.getValue()} : std::vector<std::string>{});
	const Stats stats = runPipeline(request, loader);
	if (!quiet.getValue())
	{
		std::cout << "esif run: " << statText(*stats.get("label")) << " on " << request.rawlog_path << " -> "
				  << request.out_dir << "\n";
		for (const char* key : {"steps", "landmarks", "wall_s", "step_us_p50", "step_us_p99", "state_dim", "da_wrong",
								"landmark_rmse_m", "ate_rmse_m", "landmark_consistent_fraction"})
			std::cout << "  " << key << " = " << statText(stats.get(key).value_or(nullptr)) << "\n";
	}
	return 0;
}

}  // namespace esif::app
