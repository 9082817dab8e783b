#include "CommandLine.h"
#include "Commands.h"

#include <esif/core/Errors.h>
#include <esif/eval/LocalMapFolderSummary.h>
#include <esif/eval/MonteCarloStatistics.h>
#include <esif/formats/LocalMapFiles.h>
#include <esif/localmaps/LocalMapBuild.h>
#include <esif/localmaps/LocalMapCheck.h>

#include <cstdio>
#include <cstring>
#include <iostream>

namespace esif::app
{
namespace
{
const char* const kUsage =
	"usage: esif localmaps <action> [options]   (esif localmaps <action> --help for details)\n\n"
	"actions:\n"
	"  build     build local maps from a rawlog with a joining plugin's builder settings\n"
	"  info      summarise a folder of local maps (sizes, ground truth, maps sharing < 2 features)\n"
	"  check     consistency of each local map and of the joined state after each fusion, against the truth or "
	"a reference run\n";

/// The options `build` and `check` share: where the maps come from and
/// where the result goes.
struct RawlogMapArgs
{
	TCLAP::ValueArg<std::string> config, rawlog, ground_truth, out, plugin_dir;
	TCLAP::SwitchArg quiet;

	explicit RawlogMapArgs(TCLAP::CmdLine& cmd)
		: config("c", "config", "INI file whose [esif] plugin is a local-map joining plugin", true, "", "FILE", cmd),
		  rawlog("r", "rawlog", "MRPT rawlog (gz or plain)", true, "", "FILE", cmd),
		  ground_truth("g", "ground-truth",
					   "ground-truth prefix P (P_ground_truth.txt, ...); default: beside the rawlog", false, "",
					   "PREFIX", cmd),
		  out("o", "out", "folder to write (replaced once complete)", true, "", "DIR", cmd),
		  plugin_dir("", "plugin-dir", "extra folder to search for plugins", false, "", "DIR", cmd),
		  quiet("q", "quiet", "no progress bar and no summary", cmd)
	{
	}

	template <class Request>
	void fill(Request& request)
	{
		request.config_path = config.getValue();
		request.rawlog_path = rawlog.getValue();
		if (ground_truth.isSet()) request.ground_truth_prefix = ground_truth.getValue();
		request.out_dir = out.getValue();
		request.progress_bar = !quiet.getValue();
	}

	PluginLoader loader()
	{
		return PluginLoader::withExtraFolder(valueIfSet(plugin_dir));
	}
};

/// One paragraph: what `build` wrote.
void printBuildSummary(const LocalMapFolderSummary& s, const LocalMapBuildRequest& request, LandmarkId id_offset)
{
	char mean[32];
	std::snprintf(mean, sizeof(mean), "%.1f", s.state_dim_mean);
	std::cout << "esif localmaps build: " << s.maps << " local maps from " << s.steps << " steps of "
			  << request.rawlog_path << " -> " << request.out_dir << ": " << s.feature_entries
			  << " feature entries of " << s.distinct_ids << " distinct features, state dimension min/mean/max "
			  << s.state_dim_min << "/" << mean << "/" << s.state_dim_max << "; ground truth: ";
	if (!s.truth_landmarks && !s.truth_end_poses)
		std::cout << "none";
	else
		std::cout << s.truth_landmarks.value_or(0) << " landmarks, " << s.truth_end_poses.value_or(0) << " end poses";
	if (id_offset != 0)
		std::cout << "; feature ID = rawlog ID + " << id_offset << " (the format needs positive IDs)";
	std::cout << ".\n";
}

int buildAction(int argc, char** argv)
{
	TCLAP::CmdLine cmd(
		"Builds the local maps the config's joining plugin would fuse, from a rawlog, with the builder settings "
		"of its section, and writes them in the authors' format (localmap_k.txt), with the ground truth in "
		"local-map form (ground_truth_landmarks.txt, ground_truth_end_poses.txt, frame of pose 0) when the "
		"rawlog has it.",
		' ', ESIF_VERSION);
	RawlogMapArgs args(cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;

	LocalMapBuildRequest request;
	args.fill(request);
	PluginLoader loader = args.loader();
	const LocalMapBuildResult built = runLocalMapBuild(request, loader);
	if (!args.quiet.getValue()) printBuildSummary(summarizeLocalMapFolder(built.folder), request, built.id_offset);
	return 0;
}

/// The share of rows inside their 95% interval, and the median NEES per dof.
template <class Rows, class Nees>
std::string consistencyLine(const Rows& rows, Nees nees_of)
{
	if (rows.empty()) return "none";
	std::vector<double> per_dof;
	std::size_t inside = 0;
	for (const auto& r : rows)
	{
		const StateNees& n = nees_of(r);
		per_dof.push_back(n.nees / static_cast<double>(n.dof));
		inside += n.consistent() ? 1 : 0;
	}
	char buf[160];
	std::snprintf(buf, sizeof(buf), "%zu of %zu inside their 95%% interval, median NEES/dof %.2f", inside, rows.size(),
				  quantilesOf(per_dof).median);
	return buf;
}

int checkAction(int argc, char** argv)
{
	TCLAP::CmdLine cmd(
		"Builds the local maps the config's joining plugin would fuse from a rawlog, holds each against the "
		"reference in its start frame (NEES of the whole map, of its end pose, features inside their 95% "
		"ellipse), then fuses them one by one with the plugin and holds the whole state against the reference "
		"after each fusion. Tells whether over-confidence enters in the local maps or in their fusion. Writes "
		"local_maps_nees.csv, fusion_nees.csv and consistency.png.",
		' ', ESIF_VERSION);
	RawlogMapArgs args(cmd);
	TCLAP::ValueArg<std::string> reference_run(
		"", "reference-run",
		"run folder of a smoother on the same rawlog (the full-SLAM optimum) to use as the reference instead of the "
		"ground truth: its landmarks by the rawlog's IDs, its trajectory row k as the pose after step k",
		false, "", "DIR", cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;

	LocalMapCheckRequest request;
	args.fill(request);
	if (reference_run.isSet()) request.reference_run = reference_run.getValue();
	PluginLoader loader = args.loader();
	const LocalMapCheckResult r = runLocalMapCheck(request, loader);
	if (args.quiet.getValue()) return 0;
	std::cout << "esif localmaps check: " << request.rawlog_path << " against " << r.reference << " -> "
			  << request.out_dir << "\n  local maps: "
			  << consistencyLine(r.maps, [](const LocalMapConsistency& m) -> const StateNees& { return m.whole; })
			  << "\n  state after each fusion: "
			  << consistencyLine(r.fusions, [](const FusionConsistency& f) -> const StateNees& { return f.nees; });
	if (!r.fusions.empty())
	{
		const StateNees& last = r.fusions.back().nees;
		char buf[160];
		std::snprintf(buf, sizeof(buf), "\n  after the last fusion: NEES %.1f for %zu dof [%.1f, %.1f]", last.nees,
					  last.dof, last.lower95, last.upper95);
		std::cout << buf;
	}
	std::cout << std::endl;
	return 0;
}

int infoAction(int argc, char** argv)
{
	TCLAP::CmdLine cmd(
		"Reads a folder of local maps and prints the number of maps, the state dimension (min/mean/max), the "
		"feature entries and distinct IDs, whether ground truth is present, and the maps k >= 2 that share fewer "
		"than 2 features with maps 1..k-1 (D-SLAM map joining needs 2, book Sec. 4.4.4).",
		' ', ESIF_VERSION);
	TCLAP::UnlabeledValueArg<std::string> dir("dir", "folder of localmap_1.txt ...", true, "", "DIR", cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;
	std::cout << localMapFolderInfoText(summarizeLocalMapFolder(readLocalMapFolder(dir.getValue())), dir.getValue());
	return 0;
}
}  // namespace

int localMapsCommand(int argc, char** argv)
{
	if (argc < 2) throw ConfigError("esif localmaps: name an action: build, info or check (see --help)");
	const std::string action = argv[1];
	if (action == "--help" || action == "-h" || action == "help")
	{
		std::cout << kUsage;
		return 0;
	}
	// The action sees "esif localmaps <action>" as its program name.
	std::string prog = "esif localmaps " + action;
	argv[1] = prog.data();
	if (action == "build") return buildAction(argc - 1, argv + 1);
	if (action == "info") return infoAction(argc - 1, argv + 1);
	if (action == "check") return checkAction(argc - 1, argv + 1);
	throw ConfigError("esif localmaps: unknown action '" + action + "' (known: build, info, check)");
}

}  // namespace esif::app
