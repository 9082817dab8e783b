#include "CommandLine.h"
#include "Commands.h"

#include <esif/core/Errors.h>
#include <esif/eval/ComparisonTable.h>
#include <esif/io/AtomicFile.h>
#include <esif/io/StatsJson.h>

#include <filesystem>
#include <fstream>
#include <iostream>
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
	if (!parseCommandLine(cmd, argc, argv)) return 0;

	const auto config_list = splitCommas(configs.getValue());
	if (config_list.empty()) throw ConfigError("esif compare: --configs: no config file given");
	for (const auto& c : config_list)
		if (!fs::is_regular_file(c)) throw ConfigError(c + ": config file not found");
	ensureDirectory(out.getValue());
	const auto dirs = runFolders(config_list, out.getValue());

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

	const std::string text = comparisonText(runs);
	writeTextAtomically((fs::path(out.getValue()) / "comparison.csv").string(), comparisonCsv(runs));
	writeTextAtomically((fs::path(out.getValue()) / "comparison.md").string(),
						"# esif compare on " + rawlog.getValue() + "\n\n" + comparisonMarkdown(runs));
	std::cout << text;
	return 0;
}

}  // namespace esif::app
