/// \file TerminationCleanup.cpp
/// The signal watcher thread and its registry; see TerminationCleanup.h.

#include <esif/safeio/TerminationCleanup.h>

#include "ChildWait.h"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <filesystem>
#include <system_error>
#include <thread>
#include <vector>
#include <poll.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

namespace esif::termination
{
namespace
{
struct Registry
{
	std::mutex mutex;
	std::vector<std::string> paths;
	std::vector<pid_t> children;
	std::vector<std::pair<pid_t, int>> servers;	 ///< pid and socket
	std::function<std::string(int)> stop_note;
};

Registry& registry()
{
	static Registry r;
	return r;
}

sigset_t terminationSignals()
{
	sigset_t set;
	sigemptyset(&set);
	sigaddset(&set, SIGINT);
	sigaddset(&set, SIGTERM);
	sigaddset(&set, SIGHUP);
	return set;
}

/// Waits for a run that is not our child (one the run server forked,
/// RunServer.h): its pidfd becomes readable when it ends. Without pidfds
/// (Linux before 5.3) it is polled.
void waitForOtherProcess(pid_t pid)
{
	const int fd = static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));
	if (fd >= 0)
	{
		pollfd ended{fd, POLLIN, 0};
		while (::poll(&ended, 1, -1) < 0 && errno == EINTR)
		{
		}
		::close(fd);
		return;
	}
	while (::kill(pid, 0) == 0) ::usleep(10000);
}

/// Passes the signal on to the child runs (each cleans up its own folder)
/// and waits for them, so that no orphan keeps writing into a folder that
/// is about to be removed.
void stopChildren(const std::vector<pid_t>& children, int sig)
{
	for (const pid_t child : children) ::kill(child, sig);
	for (const pid_t child : children)
	{
		int status = 0;
		if (safeio_detail::waitForChild(child, status) < 0 && errno == ECHILD) waitForOtherProcess(child);
	}
}

/// A server ends when its socket closes, after its own children.
void stopServers(const std::vector<std::pair<pid_t, int>>& servers)
{
	for (const auto& [pid, fd] : servers)
	{
		::close(fd);
		safeio_detail::waitForChild(pid);
	}
}

/// Never throws: a folder that cannot be removed is left, to be found by
/// the next run's stale-folder sweep.
void removeRegistered(const std::vector<std::string>& paths)
{
	for (auto it = paths.rbegin(); it != paths.rend(); ++it)
	{
		std::error_code ec;
		std::filesystem::remove_all(*it, ec);
	}
}

/// One write(2): the main thread may be inside a stream write holding its
/// lock.
void writeStopNote(const std::function<std::string(int)>& note, int sig)
{
	if (!note) return;
	std::string line;
	try
	{
		// Below a progress bar, not appended to it.
		line = (::isatty(STDERR_FILENO) ? "\n" : "") + note(sig) + "\n";
	}
	catch (...)
	{
		return;
	}
	for (std::size_t done = 0; done < line.size();)
	{
		const ssize_t n = ::write(STDERR_FILENO, line.data() + done, line.size() - done);
		if (n < 0 && errno == EINTR) continue;
		if (n <= 0) return;
		done += static_cast<std::size_t>(n);
	}
}

[[noreturn]] void watch()
{
	const sigset_t set = terminationSignals();
	int sig = 0;
	while (sigwait(&set, &sig) != 0)
	{
	}
	Registry& r = registry();
	r.mutex.lock();	 // held until _exit: nothing may start a swap now
	stopChildren(r.children, sig);
	stopServers(r.servers);
	removeRegistered(r.paths);
	writeStopNote(r.stop_note, sig);
	// _exit, not exit: other threads may be inside library code that static
	// destructors would pull from under them.
	::_exit(128 + sig);
}
}  // namespace

void blockSignals()
{
	const sigset_t set = terminationSignals();
	pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

void unblockSignals()
{
	sigset_t none;
	sigemptyset(&none);
	pthread_sigmask(SIG_SETMASK, &none, nullptr);
}

namespace
{
/// The watcher thread; when none can be started (the system's thread limit)
/// the signals are unblocked instead, so that they end the process by their
/// default action rather than stay pending: a partial output is then left
/// for the next writer to sweep, as after SIGKILL.
void launchWatcher()
{
	try
	{
		std::thread(watch).detach();
	}
	catch (const std::system_error&)
	{
		unblockSignals();
	}
}
}  // namespace

void startWatcher()
{
	static std::once_flag once;
	std::call_once(once, launchWatcher);
}

void restartInForkedChild()
{
	Registry& r = registry();
	r.paths.clear();
	r.children.clear();
	r.servers.clear();
	r.stop_note = nullptr;
	launchWatcher();
}

void addPath(const std::string& path)
{
	std::lock_guard<std::mutex> lock(registry().mutex);
	registry().paths.push_back(path);
}

void removePath(const std::string& path)
{
	std::lock_guard<std::mutex> lock(registry().mutex);
	auto& paths = registry().paths;
	const auto it = std::find(paths.rbegin(), paths.rend(), path);
	if (it != paths.rend()) paths.erase(std::next(it).base());
}

void setStopNote(std::function<std::string(int)> note)
{
	std::lock_guard<std::mutex> lock(registry().mutex);
	registry().stop_note = std::move(note);
}

void clearStopNote() { setStopNote(nullptr); }

void addChild(pid_t pid)
{
	std::lock_guard<std::mutex> lock(registry().mutex);
	registry().children.push_back(pid);
}

void removeChild(pid_t pid)
{
	std::lock_guard<std::mutex> lock(registry().mutex);
	auto& children = registry().children;
	children.erase(std::remove(children.begin(), children.end(), pid), children.end());
}

void addServer(pid_t pid, int fd)
{
	std::lock_guard<std::mutex> lock(registry().mutex);
	registry().servers.emplace_back(pid, fd);
}

void removeServer(pid_t pid)
{
	std::lock_guard<std::mutex> lock(registry().mutex);
	auto& servers = registry().servers;
	servers.erase(
		std::remove_if(servers.begin(), servers.end(), [pid](const auto& s) { return s.first == pid; }), servers.end());
}

std::unique_lock<std::mutex> holdOff() { return std::unique_lock<std::mutex>(registry().mutex); }

}  // namespace esif::termination
