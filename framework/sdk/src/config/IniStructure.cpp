#include "IniStructure.h"

#include <esif/core/Errors.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>
#include <sstream>
#include <vector>

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
/// A NUL byte makes MRPT drop the rest of the file, and other control
/// characters (but tab and carriage return) are never part of a config.
template <class Fail>
void checkCharacters(const std::string& raw, int line, const Fail& fail)
{
	for (std::size_t i = 0; i < raw.size(); ++i)
	{
		const auto c = static_cast<unsigned char>(raw[i]);
		if (c >= 0x20 || c == '\t' || c == '\r') continue;
		char code[8];
		std::snprintf(code, sizeof(code), "0x%02x", c);
		fail(line, std::string("control character ") + code + " at column " + std::to_string(i + 1) +
					   (c == 0 ? " (a NUL byte: MRPT's parser would drop the rest of the file)" : "") +
					   "; a config is plain text");
	}
}
}  // namespace

void checkIniStructure(const std::string& text, const std::string& origin)
{
	std::vector<std::string> lines;
	{
		std::istringstream in(text);
		for (std::string raw; std::getline(in, raw);) lines.push_back(raw);
	}
	std::string section;
	FirstSeen sections;
	std::map<std::string, FirstSeen> keys;	// per lower-cased section
	const auto fail = [&](int line, const std::string& what) {
		throw ConfigError(origin + ":" + std::to_string(line) + ": " + what);
	};
	const auto isCommentOrBlank = [](const std::string& s) { return s.empty() || s[0] == ';' || s[0] == '#'; };
	for (int line = 1; line <= static_cast<int>(lines.size()); ++line)
	{
		const std::string& raw = lines[static_cast<std::size_t>(line - 1)];
		checkCharacters(raw, line, fail);
		const std::string s = trimmed(raw);
		// MRPT joins a line ending in '\' with the next one: a key's value
		// or a header would take in the next line, and a comment would
		// swallow a key or header that follows (a shell command quoted in a
		// comment, continued on a comment line, is harmless).
		if (!s.empty() && s.back() == '\\')
		{
			const bool next_is_text =
				line < static_cast<int>(lines.size()) && !isCommentOrBlank(trimmed(lines[static_cast<std::size_t>(line)]));
			if (!isCommentOrBlank(s) || next_is_text)
				fail(line, "ends in '\\', which MRPT's parser joins with the next line" +
							   std::string(isCommentOrBlank(s) ? ", so that line would be lost in this comment" : "") +
							   "; esif configs have no continued lines: remove the '\\'");
		}
		if (isCommentOrBlank(s)) continue;
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
