#pragma once
/// \file CommandLine.h
/// TCLAP (shipped with MRPT) set up the esif way: usage errors are one line
/// naming the bad argument, --help prints the full usage and exits 0.

#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <optional>
#include <string>
#include <vector>

namespace esif::app
{
/// Parses argv with `cmd`; returns false when --help was printed (the caller
/// then returns 0). Throws ConfigError with one line for a bad command line.
bool parseCommandLine(TCLAP::CmdLine& cmd, int argc, char** argv);

/// The option's value when it was given on the command line, else nullopt.
template <class T>
std::optional<T> valueIfSet(TCLAP::ValueArg<T>& arg)  // TCLAP's getValue() is not const
{
	return arg.isSet() ? std::optional<T>(arg.getValue()) : std::nullopt;
}

/// Splits a comma-separated option value ("a,b,,c" -> a, b, c; empty items dropped).
std::vector<std::string> splitCommas(const std::string& text);

}  // namespace esif::app
