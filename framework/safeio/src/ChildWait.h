#pragma once
/// \file ChildWait.h
/// Waiting for one child process, the same way everywhere in safeio.

#include <cerrno>
#include <sys/types.h>
#include <sys/wait.h>

namespace esif::safeio_detail
{
/// waitpid(pid, &status, 0) retried while a signal interrupts it; returns
/// waitpid's result (pid, or -1 with errno, e.g. ECHILD) and the status in
/// `status`. Async-signal-safe: usable in a forked child and a signal path.
inline pid_t waitForChild(pid_t pid, int& status)
{
	pid_t waited;
	while ((waited = ::waitpid(pid, &status, 0)) < 0 && errno == EINTR)
	{
	}
	return waited;
}

/// The same, for callers that only need the child gone; returns its status.
inline int waitForChild(pid_t pid)
{
	int status = 0;
	waitForChild(pid, status);
	return status;
}

}  // namespace esif::safeio_detail
