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
/// The option of `cmd` that takes a value and is spelled `word` ("--robot",
/// "-r"); null for any other word (switches, positional values).
const TCLAP::Arg* valueOptionNamed(TCLAP::CmdLine& cmd, const std::string& word)
{
	for (const TCLAP::Arg* arg : cmd.getArgList())
	{
		// Positional arguments show as "<TYPE>": they have no spelling to match.
		if (!arg->isValueRequired() || arg->shortID().rfind('<', 0) == 0) continue;
		if (word == TCLAP::Arg::nameStartString() + arg->getName() ||
			(!arg->getFlag().empty() && word == TCLAP::Arg::flagStartString() + arg->getFlag()))
			return arg;
	}
	return nullptr;
}

/// TCLAP reads an empty value ("--robot ''", "--seed=") as no value and
/// leaves the option at its default, so `--robot ''` imported robot 1 and
/// `--out ''` was taken for the current folder: refused, naming the option.
void refuseEmptyValues(TCLAP::CmdLine& cmd, int argc, char** argv)
{
	for (int i = 1; i < argc; ++i)
	{
		const std::string token = argv[i];
		if (token == TCLAP::Arg::flagStartString() + TCLAP::Arg::flagStartString()) break;  // "--": no option after it
		const auto equals = token.find('=');
		const std::string word = token.substr(0, equals);
		if (!valueOptionNamed(cmd, word)) continue;
		const bool empty = equals != std::string::npos ? equals + 1 == token.size() : i + 1 < argc && !*argv[i + 1];
		if (empty)
			throw ConfigError(
				std::string(argv[0]) + ": " + printableToken(word) +
				": the value is empty (give one, or leave the option out to use its default; see --help)");
	}
}
}  // namespace

bool parseCommandLine(TCLAP::CmdLine& cmd, int argc, char** argv)
{
	refuseEmptyValues(cmd, argc, argv);
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
