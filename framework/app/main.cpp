/// \file main.cpp
/// `esif`: replays MRPT rawlogs through SLAM plugins and compares them.
/// Every error reaches the user as one line on stderr and a non-zero exit.

#include "Commands.h"

#include <esif/core/Errors.h>
#include <esif/safeio/TerminationCleanup.h>

#include <cstring>
#include <filesystem>
#include <new>
#include <iostream>
#include <string>

namespace
{
struct Subcommand
{
	const char* name;
	int (*run)(int, char**);
	const char* summary;
};

const Subcommand kSubcommands[] = {
	{"run", esif::app::runCommand, "replay a rawlog through one plugin and write maps and stats"},
	{"compare", esif::app::compareCommand, "run several configs on one rawlog and tabulate them"},
	{"simulate", esif::app::simulateCommand, "generate a rawlog and ground truth from a scenario INI"},
	{"import", esif::app::importCommand, "convert a dataset (victoria-park) into an MRPT rawlog, or a g2o solution into a run folder"},
	{"export", esif::app::exportCommand, "write a rawlog's full-SLAM problem for other solvers (g2o, GTSAM)"},
	{"plugins", esif::app::pluginsCommand, "list the plugins found and their parameters"},
	{"localmaps", esif::app::localMapsCommand, "build local maps from a rawlog, or summarise a folder of them"},
	{"montecarlo", esif::app::monteCarloCommand, "Monte Carlo campaign: ANEES and RMSE of configs over N noise draws"},
	{"bench", esif::app::benchCommand, "benchmarks (sparse: recovery methods of the sparse core)"},
};

void printUsage(std::ostream& out)
{
	out << "usage: esif <command> [options]   (esif <command> --help for details)\n\ncommands:\n";
	for (const auto& c : kSubcommands) out << "  " << c.name << std::string(12 - std::strlen(c.name), ' ') << c.summary << "\n";
}

/// Exit codes: 1 bad input, config or command line (a missing or unknown
/// command too); 3 numerical failure or out of memory; 4 unexpected
/// internal error; 128 + N stopped by signal N.
int dispatch(int argc, char** argv)
{
	if (argc < 2)
		throw esif::ConfigError("no command given (usage: esif <command> [options]; esif --help lists the commands)");
	const std::string name = argv[1];
	if (name == "--help" || name == "-h" || name == "help")
	{
		printUsage(std::cout);
		return 0;
	}
	for (const auto& c : kSubcommands)
		if (name == c.name)
		{
			// The subcommand sees "esif <command>" as its program name.
			std::string prog = std::string("esif ") + c.name;
			argv[1] = prog.data();
			return c.run(argc - 1, argv + 1);
		}
	throw esif::ConfigError(
		"unknown command '" + esif::printableToken(name) + "' (usage: esif <command> [options]; esif --help lists "
		"the commands)");
}
/// Prints one error line (control characters escaped, whatever a path or
/// token holds) and returns `code`.
int report(const char* kind, const std::string& what, int code)
{
	std::cerr << kind << esif::withoutControlCharacters(what) << "\n";
	return code;
}
}  // namespace

int esif::app::runMain(int argc, char** argv)
{
	try
	{
		return dispatch(argc, argv);
	}
	catch (const esif::ConfigError& e)
	{
		return report("esif: error: ", e.what(), 1);
	}
	catch (const esif::InputError& e)
	{
		return report("esif: error: ", e.what(), 1);
	}
	catch (const esif::NumericalError& e)
	{
		return report("esif: numerical failure: ", e.what(), 3);
	}
	catch (const std::filesystem::filesystem_error& e)
	{
		// A path esif could not stat, list or create that no reader checked
		// first: the path and the system's reason, an input problem.
		return report("esif: error: ", e.path1().string() + ": " + e.code().message(), 1);
	}
	catch (const std::bad_alloc&)
	{
		return report("esif: ", "out of memory", 3);
	}
	catch (const std::exception& e)
	{
		// MRPT exceptions carry a banner and a multi-line stack: one line of reason.
		return report("esif: internal error: ", esif::oneLineReason(e.what()), 4);
	}
}

int main(int argc, char** argv)
{
	// Before any thread exists (plugins and libraries start theirs later),
	// so that only the watcher receives SIGINT/SIGTERM/SIGHUP and can remove
	// partial output before exiting with 128 + the signal.
	esif::termination::blockSignals();
	esif::termination::startWatcher();
	return esif::app::runMain(argc, argv);
}
