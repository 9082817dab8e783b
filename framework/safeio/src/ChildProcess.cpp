/// \file ChildProcess.cpp
/// esif as a child process; see ChildProcess.h.

#include <esif/safeio/ChildProcess.h>

#include "ChildWait.h"

#include <esif/core/Errors.h>
#include <esif/safeio/RunServer.h>
#include <esif/safeio/TerminationCleanup.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <iostream>
#include <mutex>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace esif
{
namespace
{
/// Echoed stderr of concurrent children is written a chunk at a time.
std::mutex& echoMutex()
{
	static std::mutex m;
	return m;
}

/// Reads the pipe to its end, echoing and keeping what comes through.
std::string drain(int fd, bool echo_stderr)
{
	std::string captured;
	char buffer[4096];
	for (ssize_t n; (n = read(fd, buffer, sizeof(buffer))) != 0;)
	{
		if (n < 0 && errno == EINTR) continue;
		if (n < 0) break;
		if (echo_stderr)
		{
			std::lock_guard<std::mutex> lock(echoMutex());
			std::cerr.write(buffer, n);
		}
		captured.append(buffer, static_cast<std::size_t>(n));
	}
	return captured;
}
}  // namespace

std::string firstErrorLine(const std::string& text)
{
	std::istringstream in(text);
	std::string last;
	for (std::string line; std::getline(in, line);)
	{
		if (line.rfind("esif: ", 0) == 0 && line.rfind("esif: warning", 0) != 0) return line;
		if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
	}
	return last.empty() ? "(nothing on stderr)" : last;
}

namespace
{
/// fork + exec of /proc/self/exe: the way without a run server.
pid_t forkExec(const std::vector<std::string>& args, int stderr_fd, bool discard_stdout)
{
	std::vector<char*> argv;
	for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
	argv.push_back(nullptr);
	const pid_t pid = fork();
	if (pid != 0) return pid;
	// The child is an esif run with its own signal watcher; until its
	// main() blocks them again, a signal may end it by default. dup2
	// clears close-on-exec on the copy.
	termination::unblockSignals();
	dup2(stderr_fd, STDERR_FILENO);
	if (discard_stdout)
	{
		const int null_fd = open("/dev/null", O_WRONLY);
		if (null_fd >= 0) dup2(null_fd, STDOUT_FILENO);
		if (null_fd > STDOUT_FILENO) close(null_fd);
	}
	execv("/proc/self/exe", argv.data());
	const char message[] = "esif: error: cannot execute /proc/self/exe for the run\n";
	(void)!write(STDERR_FILENO, message, sizeof(message) - 1);
	_exit(127);
}
}  // namespace

ChildResult runEsifChild(const std::vector<std::string>& args, ChildOutput output, const std::string& who)
{
	int pipe_fds[2];
	// Close-on-exec: a child forked meanwhile by another thread must not
	// hold this pipe open (its reader would wait for that child's end).
	if (pipe2(pipe_fds, O_CLOEXEC) != 0) throw InputError(who + ": cannot start a run: pipe failed");
	std::cout.flush();
	std::cerr.flush();
	const bool discard_stdout = output == ChildOutput::Kept;
	ServedRun served;
	if (runServerStarted()) served = startServedRun(args, pipe_fds[1], discard_stdout);
	const pid_t pid = served.pid > 0 ? served.pid : forkExec(args, pipe_fds[1], discard_stdout);
	if (pid < 0)
	{
		close(pipe_fds[0]);
		close(pipe_fds[1]);
		throw InputError(who + ": cannot start a run: fork failed");
	}
	// A signal to the parent is passed on to this child and waited for.
	termination::addChild(pid);
	close(pipe_fds[1]);
	ChildResult result;
	result.stderr_text = drain(pipe_fds[0], output == ChildOutput::Shown);
	close(pipe_fds[0]);
	const int status = served.pid > 0 ? waitServedRun(served) : safeio_detail::waitForChild(pid);
	termination::removeChild(pid);
	if (WIFEXITED(status))
		result.exit_code = WEXITSTATUS(status);
	else
	{
		result.exit_code = 128 + WTERMSIG(status);
		result.stderr_text +=
			"killed by signal " + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")\n";
	}
	if (result.exit_code != 0) result.error_line = firstErrorLine(result.stderr_text);
	return result;
}

}  // namespace esif
