#include "CommandLine.h"

#include <esif/core/Errors.h>

#include <mrpt/3rdparty/tclap/StdOutput.h>

#include <algorithm>
#include <sstream>

namespace esif::app
{
namespace
{
/// TCLAP's message with every word (which may be the user's token) shown
/// by printableToken: printable ASCII, cut at 80 characters.
std::string printableWords(const std::string& text)
{
	std::string out;
	for (std::size_t at = 0; at < text.size();)
	{
		const std::size_t end = std::min(text.find(' ', at), text.size());
		out += printableToken(text.substr(at, end - at)) + (end < text.size() ? " " : "");
		at = end + 1;
	}
	return out;
}

/// Usage errors become one ConfigError line instead of TCLAP's multi-line
/// message; --help keeps TCLAP's full usage text.
class OneLineOutput : public TCLAP::StdOutput
{
   public:
	void failure(TCLAP::CmdLineInterface& cmd, TCLAP::ArgException& e) override
	{
		std::string what = e.error();
		if (e.argId() != " ") what = e.argId() + ": " + what;
		throw ConfigError(cmd.getProgramName() + ": " + printableWords(what) + " (see --help)");
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
