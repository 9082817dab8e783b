#pragma once
/// \file NumberText.h
/// Numbers as text, round-trip exact: the text map writers (landmarks.txt,
/// trajectory.tum) and the readers' error messages.

#include <charconv>
#include <string>

namespace esif::number_text
{
/// Appends the shortest text that parses back to exactly `v`: full round-trip
/// precision (for small step-index times, epoch timestamps and tiny variances
/// alike) without the noise digits of a fixed "%.17g".
inline void append(std::string& out, double v)
{
	char buf[32];
	const auto r = std::to_chars(buf, buf + sizeof(buf), v);
	out.append(buf, r.ptr);
}

/// The same text as a string (error messages name values this way too).
inline std::string text(double v)
{
	std::string out;
	append(out, v);
	return out;
}

}  // namespace esif::number_text
