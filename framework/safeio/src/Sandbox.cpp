#include <esif/safeio/Sandbox.h>

#include <esif/core/Errors.h>
#include <esif/safeio/TerminationCleanup.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <fcntl.h>
#include <cstdio>
#include <cstring>
#include <new>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace esif
{
namespace
{
/// What the child leaves for the parent, in a page both map.
struct SharedReport
{
	SandboxProgress progress;
	SandboxOutcome::Kind kind;
	char message[1024];
	std::uint64_t address_space_cap;
};

/// Address space the process maps now (/proc/self/statm, first field):
/// the limit is set above it, so only what the work allocates counts.
std::size_t mappedBytes()
{
	unsigned long pages = 0;
	if (FILE* f = std::fopen("/proc/self/statm", "r"))
	{
		if (std::fscanf(f, "%lu", &pages) != 1) pages = 0;
		std::fclose(f);
	}
	return static_cast<std::size_t>(pages) * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

/// A fault in the child must end it by its signal, which the parent turns
/// into a message: handlers inherited from the parent (a sanitizer's, a
/// fuzzer's, a crash reporter's) would instead treat it as the parent's own.
void restoreDefaultFaultHandlers()
{
	for (const int sig : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGXCPU}) std::signal(sig, SIG_DFL);
}

/// What the work prints (MRPT writes its own complaints about corrupt
/// entries to stderr) would add lines to the one the parent reports.
void silenceOutput()
{
	const int null = open("/dev/null", O_WRONLY);
	if (null < 0) return;
	dup2(null, STDOUT_FILENO);
	dup2(null, STDERR_FILENO);
	close(null);
}

void applyLimits(const SandboxLimits& limits, SharedReport& shared)
{
	// The child must not outlive the parent (e.g. `esif run` stopped by SIGTERM).
	prctl(PR_SET_PDEATHSIG, SIGKILL);
	if (limits.address_space_bytes > 0)
	{
		const rlim_t as = mappedBytes() + limits.address_space_bytes;
		// Above a limit the process was started under, the child keeps that
		// one: the parent must then not read a failed allocation as the
		// work's fault alone.
		rlimit inherited{};
		if (getrlimit(RLIMIT_AS, &inherited) == 0 && inherited.rlim_cur != RLIM_INFINITY && inherited.rlim_cur < as)
			shared.address_space_cap = inherited.rlim_cur;
		else
		{
			const rlimit r{as, as};
			setrlimit(RLIMIT_AS, &r);
		}
	}
	if (limits.cpu_seconds > 0)
	{
		// The soft limit sends SIGXCPU, the hard one a second later SIGKILL.
		const rlimit r{limits.cpu_seconds, limits.cpu_seconds + 1};
		setrlimit(RLIMIT_CPU, &r);
	}
}

void report(SharedReport& shared, SandboxOutcome::Kind kind, const char* message)
{
	shared.kind = kind;
	std::strncpy(shared.message, message, sizeof(shared.message) - 1);
	shared.message[sizeof(shared.message) - 1] = '\0';
}

[[noreturn]] void runChild(const std::function<void(SandboxProgress&)>& work, const SandboxLimits& limits,
						   SharedReport& shared)
{
	restoreDefaultFaultHandlers();
	// The parent blocks SIGINT/SIGTERM for its watcher thread; here they must
	// end the child (the watcher forwards them to it, and Ctrl-C reaches it).
	termination::unblockSignals();
	silenceOutput();
	applyLimits(limits, shared);
	try
	{
		work(shared.progress);
		report(shared, SandboxOutcome::Kind::kSucceeded, "");
	}
	catch (const std::bad_alloc&)
	{
		report(shared, SandboxOutcome::Kind::kOutOfMemory, "");
	}
	catch (const std::exception& e)
	{
		// Libraries may wrap an allocation failure in their own exception.
		const bool oom = std::strstr(e.what(), "bad_alloc") != nullptr;
		report(shared, oom ? SandboxOutcome::Kind::kOutOfMemory : SandboxOutcome::Kind::kFailed, e.what());
	}
	catch (...)
	{
		report(shared, SandboxOutcome::Kind::kFailed, "unknown exception");
	}
	_exit(0);
}

int waitFor(pid_t pid)
{
	int status = 0;
	while (waitpid(pid, &status, 0) < 0)
		if (errno != EINTR) return -1;
	return status;
}

SandboxOutcome outcomeOf(int status, const SharedReport& shared)
{
	SandboxOutcome out;
	out.position = shared.progress.position;
	out.result = shared.progress.result;
	out.address_space_cap = shared.address_space_cap;
	if (status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0)
	{
		out.kind = shared.kind;
		out.message = shared.message;
		return out;
	}
	if (status != -1 && WIFEXITED(status))
	{
		// The work ended the child itself (a sanitizer's report, a library's exit()).
		out.kind = SandboxOutcome::Kind::kCrashed;
		out.message = "it exited with status " + std::to_string(WEXITSTATUS(status));
		return out;
	}
	const int sig = status != -1 && WIFSIGNALED(status) ? WTERMSIG(status) : 0;
	if (sig == SIGINT || sig == SIGTERM || sig == SIGHUP)
	{
		out.kind = SandboxOutcome::Kind::kInterrupted;
		out.signal_number = sig;
		return out;
	}
	// SIGKILL follows SIGXCPU when the hard CPU limit is reached.
	out.kind = (sig == SIGXCPU || sig == SIGKILL) ? SandboxOutcome::Kind::kCpuLimit : SandboxOutcome::Kind::kCrashed;
	out.signal_number = sig;
	return out;
}
}  // namespace

SandboxOutcome runInSandbox(const std::function<void(SandboxProgress&)>& work, const SandboxLimits& limits)
{
	void* page = mmap(nullptr, sizeof(SharedReport), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
	if (page == MAP_FAILED) throw InputError(std::string("cannot start the sandboxed reader: ") + std::strerror(errno));
	auto* shared = new (page) SharedReport{};
	shared->kind = SandboxOutcome::Kind::kCrashed;	// until the child says otherwise
	std::fflush(nullptr);  // no buffered output may be written twice
	const pid_t pid = fork();
	if (pid < 0)
	{
		munmap(page, sizeof(SharedReport));
		throw InputError(std::string("cannot start the sandboxed reader: fork: ") + std::strerror(errno));
	}
	if (pid == 0) runChild(work, limits, *shared);
	// A signal that ends esif meanwhile must end the child too, and reap it.
	termination::addChild(pid);
	const SandboxOutcome out = outcomeOf(waitFor(pid), *shared);
	termination::removeChild(pid);
	munmap(page, sizeof(SharedReport));
	return out;
}

}  // namespace esif
