#pragma once
/// \file IniStructure.h
/// What MRPT's INI parser accepts silently and esif refuses: it merges a
/// repeated section or key (case-insensitively, the last value winning),
/// swallows the lines after a malformed `[` header into a section of that
/// name and skips lines that are neither a header, a `key = value` nor a
/// comment; it joins a line ending in `\` with the next and stops at a NUL
/// byte. A config with any of these is ambiguous, so it is an error.

#include <string>

namespace esif
{
/// Throws ConfigError "origin:line: ..." at the first structural fault of
/// INI `text`: a header that is not `[name]`, a line that is not a header,
/// `key = value`, comment (';' or '#') or blank, a section or key (within
/// its section) that appears a second time, compared case-insensitively as
/// MRPT does, a line ending in `\` (a continuation) and a control character
/// other than tab and carriage return (a NUL byte among them).
void checkIniStructure(const std::string& text, const std::string& origin);

}  // namespace esif
