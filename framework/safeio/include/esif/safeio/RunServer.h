#pragma once
/// \file RunServer.h
/// A fork server for child runs, the pattern of Android's zygote and
/// Chromium's: `esif compare` and `esif montecarlo` start it while they are
/// still single-threaded, and every child run is then a fork of it that
/// calls esif's entry point directly instead of executing /proc/self/exe
/// again. A fresh esif process spends about 0.15 s in the dynamic loader
/// (MRPT's Debian libraries pull in some 300 shared objects, all bound at
/// load time); a campaign of 200 short runs paid that 200 times.
///
/// Each run stays a process of its own, as with exec: its own memory,
/// signal watcher, exit code and stderr, and a crash ends only it. The
/// server is single-threaded, so forking it is safe where forking a parent
/// that runs job threads is not. runEsifChild (ChildProcess.h) uses the
/// server when one is running and falls back to fork + exec otherwise.

#include <string>
#include <sys/types.h>
#include <vector>

namespace esif
{
/// esif's entry point as a child run calls it: argv as main() receives it
/// ("esif", "<command>", ...); returns the exit code.
using EntryPoint = int (*)(int argc, char** argv);

/// The server for as long as this object lives. Construct it while only
/// the main thread and the signal watcher exist, before taking locks or
/// opening files a run must not inherit; one at a time. If it cannot start
/// (no fork, no socket), runs fall back to exec. The destructor, or the
/// signal watcher if a signal ends esif first, closes the server's socket
/// and waits for it; the server waits for its runs' helpers first, so that
/// no process of esif outlives it.
class RunServer
{
   public:
	explicit RunServer(EntryPoint entry);
	~RunServer();
	RunServer(const RunServer&) = delete;
	RunServer& operator=(const RunServer&) = delete;

   private:
	pid_t pid_ = -1;
};

/// True while a RunServer is running.
bool runServerStarted();

/// One run forked by the server: its stderr goes to `stderr_fd` (which this
/// call does not close), its stdout to ours or, with `discard_stdout`, to
/// /dev/null. Returns the run's pid once it exists, or -1 if the server is
/// gone; waitRun then returns its wait status.
struct ServedRun
{
	pid_t pid = -1;
	int reply_fd = -1;	///< the helper that waits for the run reports its status here
};
ServedRun startServedRun(const std::vector<std::string>& args, int stderr_fd, bool discard_stdout);

/// Blocks until the run has ended; returns its wait status (as waitpid's)
/// and closes the reply descriptor. A helper that vanished without a
/// status reads as a run killed by SIGKILL.
int waitServedRun(ServedRun& run);

}  // namespace esif
