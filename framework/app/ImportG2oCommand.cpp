#include "CommandLine.h"
#include "Commands.h"

#include <esif/interop/G2oImport.h>

#include <iostream>

namespace esif::app
{
int importG2oCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd(
		"Reads a g2o solution (the file `esif export g2o` wrote, or a solver's optimised output with the same "
		"vertices) into a run folder's trajectory.tum and landmarks.txt, for esif compare --reference.",
		' ', ESIF_VERSION);
	TCLAP::ValueArg<std::string> g2o("", "g2o", "g2o file", true, "", "FILE", cmd);
	TCLAP::ValueArg<std::string> rawlog(
		"r", "rawlog", "the rawlog the file was exported from (gives each step's time and pose)", true, "", "FILE",
		cmd);
	TCLAP::ValueArg<std::string> out("o", "out", "run folder to write", true, "", "DIR", cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;
	const auto s = importG2oSolution(g2o.getValue(), rawlog.getValue(), out.getValue());
	std::cout << "esif import: " << out.getValue() << ": " << s.steps << " steps (" << s.poses << " poses), "
			  << s.landmarks << " landmarks\n";
	return 0;
}

}  // namespace esif::app
