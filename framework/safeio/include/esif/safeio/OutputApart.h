#pragma once
/// \file OutputApart.h
/// An output never replaces an input: every command checks, before it
/// writes anything, that its output (a file or a folder) is not one of its
/// inputs, does not lie inside an input folder and does not hold an input
/// (replacing the folder would delete it). Paths are compared after
/// resolving symbolic links, `.` and `..`, so another spelling of the same
/// path is caught too.

#include <string>
#include <vector>

namespace esif
{
/// An input path and what it is, for the message ("the rawlog").
struct NamedInput
{
	std::string what;
	std::string path;
};

/// Throws InputError "OUT: OPTION is|holds|lies inside WHAT PATH ..." when
/// `out` (given as `option`) and any input overlap; inputs with an empty
/// path are skipped.
void requireOutputApart(
	const std::string& out, const std::vector<NamedInput>& inputs, const std::string& option = "--out");

}  // namespace esif
