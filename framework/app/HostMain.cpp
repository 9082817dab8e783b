/// \file HostMain.cpp
/// The host of `esif` (libesif_app.so): replays MRPT rawlogs through SLAM
/// plugins and compares them. The `esif` executable is the launcher that
/// loads it (launcher/Launcher.cpp).
/// Every error reaches the user as one line on stderr and a non-zero exit.

#include "CommandList.h"
#include "Commands.h"
#include "TerminalStreams.h"

#include <esif/core/Errors.h>
#include <esif/safeio/TerminationCleanup.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <string>

namespace
{
struct Subcommand
{
	const char* name;
	int (*run)(int, char**);
};

/// Every name of kCommandSummaries (CommandList.h), with its function.
constexpr Subcommand kSubcommands[] = {
	{"run", esif::app::runCommand},
	{"compare", esif::app::compareCommand},
	{"simulate", esif::app::simulateCommand},
	{"import", esif::app::importCommand},
	{"export", esif::app::exportCommand},
	{"plugins", esif::app::pluginsCommand},
	{"localmaps", esif::app::localMapsCommand},
	{"montecarlo", esif::app::monteCarloCommand},
	{"bench", esif::app::benchCommand},
	{"calibrate", esif::app::calibrateCommand},
};
constexpr bool sameText(const char* a, const char* b) { return *a == *b && (*a == '\0' || sameText(a + 1, b + 1)); }

constexpr bool namesMatchTheSummaries()
{
	if (std::size(kSubcommands) != std::size(esif::app::kCommandSummaries)) return false;
	for (std::size_t i = 0; i < std::size(kSubcommands); ++i)
		if (!sameText(kSubcommands[i].name, esif::app::kCommandSummaries[i].name)) return false;
	return true;
}
static_assert(namesMatchTheSummaries(), "kSubcommands and kCommandSummaries list the same commands in the same order");

/// Exit codes: 1 bad input, config or command line (a missing or unknown
/// command too); 3 numerical failure or out of memory; 4 unexpected
/// internal error; 128 + N stopped by signal N.
int dispatch(int argc, char** argv)
{
	if (argc < 2)
		throw esif::ConfigError("no command given (usage: esif <command> [options]; esif --help lists the commands)");
	const std::string name = argv[1];
	if (esif::app::isHelpRequest(name))
	{
		esif::app::printUsage(std::cout);
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
}  // namespace

int esif::app::runMain(int argc, char** argv)
{
	try
	{
		return dispatch(argc, argv);
	}
	catch (...)
	{
		const esif::FailureReport failure = esif::reportCurrentException();
		std::cerr << failure.line << "\n";
		return failure.exit_code;
	}
}

/// The host's entry point, which the launcher (launcher/Launcher.cpp) calls
/// once it has loaded this library.
extern "C" __attribute__((visibility("default"))) int esif_app_main(int argc, char** argv)
{
	// Before any thread exists (plugins and libraries start theirs later),
	// so that only the watcher receives SIGINT/SIGTERM/SIGHUP and can remove
	// partial output before exiting with 128 + the signal.
	esif::termination::blockSignals();
	esif::termination::startWatcher();
	esif::app::filterTerminalStreams();
	const int code = esif::app::runMain(argc, argv);
	// Every output is written, synced and in place by now (AtomicFile.h):
	// end without running the static destructors of the ~300 libraries the
	// host loaded, which only free memory the kernel reclaims anyway (as
	// clang's -disable-free does). Streams are flushed first.
	esif::app::finishTerminalStreams();
	std::fflush(nullptr);
	std::_Exit(code);
}
