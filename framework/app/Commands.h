#pragma once
/// \file Commands.h
/// The subcommands of the `esif` host. Each takes the arguments after its
/// name (argv[0] is "esif <command>"), prints its own --help, and returns the
/// process exit code. Errors are thrown as esif::ConfigError / InputError /
/// NumericalError and turned into one line on stderr by runMain().

#include <string>
#include <vector>

namespace esif::app
{
/// Everything esif_app_main() (HostMain.cpp) does after blocking the
/// termination signals and starting their watcher: dispatches argv ("esif", "<command>", ...) and
/// turns an exception into one error line and the exit code. Also what a
/// run forked by the run server calls (RunServer.h).
int runMain(int argc, char** argv);

int runCommand(int argc, char** argv);
int compareCommand(int argc, char** argv);
int simulateCommand(int argc, char** argv);
int pluginsCommand(int argc, char** argv);
/// What `esif plugins` prints: the folders searched (`extra_dirs`, then
/// ESIF_PLUGIN_PATH, then ../lib/esif beside the executable), the host's
/// [esif] keys and each plugin's parameters with their defaults.
std::string pluginListing(const std::vector<std::string>& extra_dirs);
int importCommand(int argc, char** argv);
int benchCommand(int argc, char** argv);
int localMapsCommand(int argc, char** argv);
int exportCommand(int argc, char** argv);
/// `esif import g2o`, which importCommand hands g2o input to.
int importG2oCommand(int argc, char** argv);
int monteCarloCommand(int argc, char** argv);
int calibrateCommand(int argc, char** argv);

}  // namespace esif::app
