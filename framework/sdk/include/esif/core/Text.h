#pragma once
/// \file Text.h
/// Small string helpers shared by the host's files and commands.

#include <string>

namespace esif
{
/// `text` with every occurrence of `from` (not empty; an empty `from`
/// changes nothing) replaced by `to`, left to right, replacements not rescanned.
inline std::string replaceAll(std::string text, const std::string& from, const std::string& to)
{
	for (std::size_t at = 0; !from.empty() && (at = text.find(from, at)) != std::string::npos; at += to.size())
		text.replace(at, from.size(), to);
	return text;
}

/// Whether `text` holds a C0 control character or DEL, a line break among
/// them: such a text cannot be one value of a line-based file (a job list,
/// campaign.ini, the record of a file set).
inline bool holdsControlCharacter(const std::string& text)
{
	for (const char c : text)
		if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return true;
	return false;
}

}  // namespace esif
