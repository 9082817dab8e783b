#pragma once
/// \file CommandList.h
/// The names and one-line summaries of esif's commands, shared by the
/// launcher (which prints them for --help without loading the host) and the
/// host (which maps each name to its function, HostMain.cpp).

#include <cstring>
#include <ostream>
#include <string>

namespace esif::app
{
struct CommandSummary
{
	const char* name;
	const char* summary;
};

inline constexpr CommandSummary kCommandSummaries[] = {
	{"run", "replay a rawlog through one plugin and write maps and stats"},
	{"compare", "run several configs on one rawlog and tabulate them"},
	{"simulate", "generate a rawlog and ground truth from a scenario INI"},
	{"import", "convert a dataset (victoria-park) into an MRPT rawlog, or a g2o solution into a run folder"},
	{"export", "write a rawlog's full-SLAM problem for other solvers (g2o, GTSAM)"},
	{"plugins", "list the plugins found and their parameters"},
	{"localmaps", "build local maps from a rawlog, or summarise a folder of them"},
	{"montecarlo", "Monte Carlo campaign: ANEES and RMSE of configs over N noise draws"},
	{"bench", "benchmarks (sparse: recovery methods of the sparse core)"},
	{"calibrate", "fit a rawlog's noise model by maximum likelihood against a reference"},
};

inline bool isHelpRequest(const std::string& word) { return word == "--help" || word == "-h" || word == "help"; }

inline void printUsage(std::ostream& out)
{
	out << "usage: esif <command> [options]   (esif <command> --help for details)\n\ncommands:\n";
	for (const auto& c : kCommandSummaries)
		out << "  " << c.name << std::string(12 - std::strlen(c.name), ' ') << c.summary << "\n";
}

}  // namespace esif::app
