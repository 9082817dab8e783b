#include "CommandLine.h"

#include <esif/core/Errors.h>

#include <mrpt/3rdparty/tclap/StdOutput.h>

#include <sstream>

namespace esif::app
{
namespace
{
/// Usage errors become one ConfigError line instead of TCLAP's multi-line
/// message; --help keeps TCLAP's full usage text.
class OneLineOutput : public TCLAP::StdOutput
{
   public:
	void failure(TCLAP::CmdLineInterface& cmd, TCLAP::ArgException& e) override
	{
		std::string what = e.error();
		if (e.argId() != " ") what = e.argId() + ": " + what;
		throw ConfigError(cmd.getProgramName() + ": " + what + " (see --help)");
	}
};
}  // namespace

bool parseCommandLine(TCLAP::CmdLine& cmd, int argc, char** argv)
{
	OneLineOutput output;
	cmd.setOutput(&output);
	const bool go_on = cmd.parse(argc, argv);
	cmd.setOutput(nullptr);
	return go_on;
}

std::vector<std::string> splitCommas(const std::string& text)
{
	std::vector<std::string> out;
	std::stringstream ss(text);
	std::string item;
	while (std::getline(ss, item, ','))
		if (!item.empty()) out.push_back(item);
	return out;
}

}  // namespace esif::app
