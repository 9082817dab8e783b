#include "IniStructure.h"

#include <esif/core/Errors.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <sstream>

namespace esif
{
namespace
{
std::string trimmed(const std::string& s)
{
	const auto first = s.find_first_not_of(" \t\r");
	if (first == std::string::npos) return "";
	return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

std::string lowered(std::string s)
{
	std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
	return s;
}

/// First line of each name seen so far, keyed case-insensitively.
class FirstSeen
{
   public:
	/// The line where `name` was first seen, or 0 when it is new (then recorded at `line`).
	int previous(const std::string& name, int line)
	{
		const auto [it, inserted] = lines_.emplace(lowered(name), line);
		return inserted ? 0 : it->second;
	}

   private:
	std::map<std::string, int> lines_;
};
}  // namespace

void checkIniStructure(const std::string& text, const std::string& origin)
{
	std::istringstream in(text);
	std::string raw, section;
	FirstSeen sections;
	std::map<std::string, FirstSeen> keys;	// per lower-cased section
	const auto fail = [&](int line, const std::string& what) {
		throw ConfigError(origin + ":" + std::to_string(line) + ": " + what);
	};
	for (int line = 1; std::getline(in, raw); ++line)
	{
		const std::string s = trimmed(raw);
		if (s.empty() || s[0] == ';' || s[0] == '#') continue;
		if (s[0] == '[')
		{
			if (s.size() < 3 || s.back() != ']' || s.find(']') != s.size() - 1)
				fail(line, "'" + s + "' is not a section header of the form [name]");
			section = trimmed(s.substr(1, s.size() - 2));
			if (section.empty()) fail(line, "'" + s + "' is not a section header of the form [name]");
			if (const int first = sections.previous(section, line))
				fail(line, "section [" + section + "] appears again (first at line " + std::to_string(first) +
							   "; names are compared ignoring case)");
			continue;
		}
		const auto eq = s.find('=');
		if (eq == std::string::npos || trimmed(s.substr(0, eq)).empty())
			fail(line, "'" + s + "' is neither a [section], a key = value line nor a comment");
		const std::string key = trimmed(s.substr(0, eq));
		if (const int first = keys[lowered(section)].previous(key, line))
			fail(line, "key '" + key + "'" + (section.empty() ? "" : " in [" + section + "]") +
						   " appears again (first at line " + std::to_string(first) +
						   "; names are compared ignoring case)");
	}
}

}  // namespace esif
