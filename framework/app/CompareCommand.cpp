#include "CommandLine.h"
#include "Commands.h"

#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/eval/ComparisonTable.h>
#include <esif/eval/RunDifference.h>
#include <esif/io/AtomicFile.h>
#include <esif/io/RunOutputReader.h>
#include <esif/io/StatsJson.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace esif::app
{
namespace
{
/// Each config runs as its own `esif run` process: its wall time and peak
/// memory are then its own, and one plugin cannot disturb the next.
int runChild(const std::vector<std::string>& args)
{
	std::vector<char*> argv;
	for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
	argv.push_back(nullptr);
	const pid_t pid = fork();
	if (pid < 0) throw InputError("compare: cannot start a run: fork failed");
	if (pid == 0)
	{
		execv("/proc/self/exe", argv.data());
		_exit(127);
	}
	int status = 0;
	waitpid(pid, &status, 0);
	return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// One output folder per config, named after the file (a suffix keeps repeats apart).
std::vector<std::string> runFolders(const std::vector<std::string>& configs, const std::string& out)
{
	std::vector<std::string> dirs;
	std::set<std::string> used;
	for (const auto& c : configs)
	{
		std::string name = fs::path(c).stem().string();
		for (int k = 2; used.count(name); ++k) name = fs::path(c).stem().string() + "_" + std::to_string(k);
		used.insert(name);
		dirs.push_back((fs::path(out) / name).string());
	}
	return dirs;
}

/// The label a config's run will carry: its [esif] label, else the config
/// file name (as the run pipeline sets it). Known before running, so that a
/// wrong --reference fails at once.
std::string configLabel(const ConfigFile& config)
{
	const std::string label = config.section("esif").getString("label", "");
	return label.empty() ? fs::path(config.origin()).stem().string() : label;
}

/// Index of the run `reference` names: by label, else (or among runs of
/// one label) by run folder name.
std::size_t referenceIndex(
	const std::string& reference, const std::vector<std::string>& configs, const std::vector<std::string>& labels,
	const std::vector<std::string>& dirs)
{
	std::vector<std::size_t> hits;
	for (std::size_t i = 0; i < labels.size(); ++i)
		if (labels[i] == reference) hits.push_back(i);
	if (hits.empty())
		for (std::size_t i = 0; i < dirs.size(); ++i)
			if (fs::path(dirs[i]).filename().string() == reference) hits.push_back(i);
	if (hits.size() > 1)  // one label, several configs: their run folders still differ
		for (const auto i : hits)
			if (fs::path(dirs[i]).filename().string() == reference) return i;
	if (hits.size() == 1) return hits.front();
	std::string list;
	if (hits.empty())
	{
		for (const auto& l : labels) list += (list.empty() ? "" : ", ") + l;
		throw ConfigError(
			"esif compare: --reference '" + reference + "': not the label of a compared run (labels: " + list + ")");
	}
	std::string folders;
	for (const auto i : hits)
	{
		list += (list.empty() ? "" : ", ") + configs[i];
		folders += (folders.empty() ? "" : ", ") + fs::path(dirs[i]).filename().string();
	}
	throw ConfigError(
		"esif compare: --reference '" + reference + "': several runs have this label (" + list +
		"); name one of their run folders (" + folders + ") or give each config its own [esif] label");
}

Stats readStats(const std::string& path)
{
	std::ifstream in(path);
	if (!in) throw InputError(path + ": missing after the run");
	std::stringstream ss;
	ss << in.rdbuf();
	return Stats::fromJson(ss.str(), path);
}
}  // namespace

int compareCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd("Runs several configs on one rawlog, each in its own process, and tabulates them.", ' ',
					   ESIF_VERSION);
	TCLAP::ValueArg<std::string> configs("c", "configs", "comma-separated INI files", true, "", "A.ini,B.ini,...", cmd);
	TCLAP::ValueArg<std::string> rawlog("r", "rawlog", "MRPT rawlog (gz or plain)", true, "", "FILE", cmd);
	TCLAP::ValueArg<std::string> ground_truth("g", "ground-truth", "ground-truth prefix; default: beside the rawlog",
											  false, "", "PREFIX", cmd);
	TCLAP::ValueArg<std::string> out("o", "out", "output folder (one subfolder per config)", true, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> plugin_dir("", "plugin-dir", "extra folder to search for plugins", false, "", "DIR",
											cmd);
	TCLAP::ValueArg<std::string> reference(
		"", "reference",
		"label of the run the others are compared with (for data without ground truth): adds each run's "
		"difference from it, in the shared initial-pose frame without alignment, as ref_traj_rms_m, "
		"ref_traj_max_m, ref_heading_rms_deg (poses of the same step), ref_landmark_rms_m, ref_landmark_max_m "
		"and ref_landmarks_matched (landmarks with the same ID: the runs must use the rawlog's landmark IDs). "
		"The reference's row shows zeros and its own landmark count",
		false, "", "LABEL", cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;

	const auto config_list = splitCommas(configs.getValue());
	if (config_list.empty()) throw ConfigError("esif compare: --configs: no config file given");
	for (const auto& c : config_list)
		if (!fs::is_regular_file(c)) throw ConfigError(c + ": config file not found");
	const auto dirs = runFolders(config_list, out.getValue());
	std::optional<std::size_t> ref;
	if (reference.isSet())
	{
		std::vector<ConfigFile> parsed;
		std::vector<std::string> labels;
		for (const auto& c : config_list)
		{
			parsed.push_back(ConfigFile::load(c));
			labels.push_back(configLabel(parsed.back()));
		}
		ref = referenceIndex(reference.getValue(), config_list, labels, dirs);
		// Landmarks are paired by ID: a filter that associates on its own numbers them itself.
		for (const auto& config : parsed)
			if (config.section("esif").getBool("hide_landmark_ids", false))
				std::cerr << "esif: warning: " << config.origin()
						  << ": hide_landmark_ids = true: its landmarks carry its own IDs, so ref_landmark_* pair "
							 "landmarks of unrelated IDs\n";
	}
	ensureDirectory(out.getValue());

	std::vector<Stats> runs;
	for (std::size_t i = 0; i < config_list.size(); ++i)
	{
		std::vector<std::string> args = {"esif", "run", "--quiet", "--config", config_list[i], "--rawlog",
										 rawlog.getValue(), "--out", dirs[i]};
		if (ground_truth.isSet()) args.insert(args.end(), {"--ground-truth", ground_truth.getValue()});
		if (plugin_dir.isSet()) args.insert(args.end(), {"--plugin-dir", plugin_dir.getValue()});
		std::cerr << "esif compare: running " << config_list[i] << "\n";
		if (const int code = runChild(args); code != 0)
			throw InputError("compare: the run of " + config_list[i] + " failed (exit " + std::to_string(code) + ")");
		runs.push_back(readStats((fs::path(dirs[i]) / "stats.json").string()));
	}

	std::string note;
	if (ref)
	{
		const RunOutputs reference_outputs = readRunOutputs(dirs[*ref]);
		for (std::size_t i = 0; i < runs.size(); ++i)
			setDifferenceStats(
				runs[i], i == *ref ? referenceItself(reference_outputs)
								   : runDifference(readRunOutputs(dirs[i]), reference_outputs));
		note = "ref_*: difference from run '" + reference.getValue() +
			   "' in the initial-pose frame, no alignment (trajectory by step, landmarks by ID)\n";
	}

	const std::string text = comparisonText(runs) + note;
	writeTextAtomically((fs::path(out.getValue()) / "comparison.csv").string(), comparisonCsv(runs));
	writeTextAtomically((fs::path(out.getValue()) / "comparison.md").string(),
						"# esif compare on " + rawlog.getValue() + "\n\n" + comparisonMarkdown(runs) +
							(note.empty() ? "" : "\n" + note));
	std::cout << text;
	return 0;
}

}  // namespace esif::app
