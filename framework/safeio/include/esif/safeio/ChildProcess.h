#pragma once
/// \file ChildProcess.h
/// Runs esif itself as a child process, as `esif compare` and `esif
/// montecarlo` run each `esif run`: a fork of the run server when one is
/// running (RunServer.h), else /proc/self/exe executed again. Either way
/// its wall time and peak memory are its own, and a crash ends only it. A
/// signal to the parent is passed on to every running child and waited for
/// (TerminationCleanup.h). Safe to call from several threads at once.

#include <string>
#include <vector>

namespace esif
{
/// What a child run left behind: its exit code (128 + N when killed by
/// signal N) and the line of its stderr that says why it failed.
struct ChildResult
{
	int exit_code = 0;
	std::string error_line;	 ///< empty when exit_code is 0
	std::string stderr_text;  ///< all it wrote to stderr
};

/// How much of a child's output reaches the terminal.
enum class ChildOutput
{
	Shown,	///< stdout inherited, stderr passed on to ours as it arrives (and kept)
	Kept	///< stdout discarded, stderr only kept (many children at once, a progress bar)
};

/// Runs `args` (args[0] is the program name the child sees, e.g. "esif").
/// Its stderr comes through a pipe and is kept for ChildResult. `who` names
/// the caller in errors ("compare", "montecarlo").
ChildResult runEsifChild(const std::vector<std::string>& args, ChildOutput output, const std::string& who);

/// The first line in which esif reports its failure ("esif: error: ...",
/// "esif: numerical failure: ...", "esif: internal error: ...": any "esif: "
/// line but a warning), else the last non-empty line (e.g. a library's
/// message, or the signal that killed the run).
std::string firstErrorLine(const std::string& text);

}  // namespace esif
