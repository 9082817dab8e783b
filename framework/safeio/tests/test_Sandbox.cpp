// The sandbox's address-space limit, and what it says when the process was
// started under a lower one (prlimit, a batch system's memory cap): the
// child then runs under that one, and a failed allocation is not the work's
// fault alone (RawlogReader.cpp words its error accordingly).

#include <esif/safeio/Sandbox.h>

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace
{
using esif::SandboxOutcome;

/// Keeps what allocate() took: an allocation nothing uses may be left out.
std::vector<std::unique_ptr<char[]>> kept;

/// Takes and touches `bytes` of fresh memory.
void allocate(std::size_t bytes)
{
	kept.emplace_back(new char[bytes]);
	std::memset(kept.back().get(), 1, bytes);
}

TEST(Sandbox, AnAllocationBeyondItsLimitIsOutOfMemoryUnderTheLimitAskedFor)
{
	const auto outcome = esif::runInSandbox([](esif::SandboxProgress&) { allocate(std::size_t{512} << 20); },
											{std::size_t{64} << 20, 0});
	EXPECT_EQ(outcome.kind, SandboxOutcome::Kind::kOutOfMemory);
	EXPECT_EQ(outcome.address_space_cap, 0u);
}

TEST(Sandbox, UnderALowerLimitTheProcessStartedWithItSaysSo)
{
	// In a child of the test, so that the test's own limit stays as it is.
	const pid_t pid = fork();
	ASSERT_GE(pid, 0);
	if (pid == 0)
	{
		rlimit low{};
		getrlimit(RLIMIT_AS, &low);
		// The address space mapped now, plus 64 MiB: below what the sandbox asks for.
		long pages = 0;
		if (FILE* f = std::fopen("/proc/self/statm", "r"))
		{
			if (std::fscanf(f, "%ld", &pages) != 1) pages = 0;
			std::fclose(f);
		}
		low.rlim_cur = low.rlim_max = static_cast<rlim_t>(pages) * sysconf(_SC_PAGESIZE) + (rlim_t{64} << 20);
		if (setrlimit(RLIMIT_AS, &low) != 0) _exit(2);
		const auto outcome = esif::runInSandbox([](esif::SandboxProgress&) { allocate(std::size_t{256} << 20); },
												{std::size_t{1} << 30, 0});
		const bool said = outcome.kind == SandboxOutcome::Kind::kOutOfMemory && outcome.address_space_cap == low.rlim_cur;
		_exit(said ? 0 : 1);
	}
	int status = 0;
	ASSERT_EQ(waitpid(pid, &status, 0), pid);
	ASSERT_TRUE(WIFEXITED(status));
	EXPECT_EQ(WEXITSTATUS(status), 0) << "the sandbox did not report the lower limit it ran under";
}
}  // namespace
