/// \file test_RunServer.cpp
/// The run server (RunServer.h) through runEsifChild, with a test entry
/// point in place of esif's: each run is a process of its own, forked by
/// the server rather than by this process; its exit code, stderr and the
/// signal that killed it come back as with fork + exec; concurrent runs
/// keep their own stderr; and no process outlives the server.

#include <esif/safeio/ChildProcess.h>
#include <esif/safeio/RunServer.h>

#include <gtest/gtest.h>

#include <csignal>
#include <cstring>
#include <iostream>
#include <string>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace
{
using esif::ChildOutput;
using esif::runEsifChild;
using esif::RunServer;

/// The runs' entry point: argv = {"esif", what, argument}.
int testEntry(int argc, char** argv)
{
	const std::string what = argc > 1 ? argv[1] : "";
	if (what == "whoami")
	{
		std::cerr << getpid() << " " << getppid() << "\n";
		return 7;
	}
	if (what == "fail")
	{
		std::cerr << "a library's chatter\nesif: error: " << argv[2] << "\nmore chatter\n";
		return 1;
	}
	if (what == "kill") ::raise(SIGKILL);
	if (what == "echo")
	{
		for (int i = 0; i < 200; ++i) std::cerr << argv[2] << "\n";
		return 0;
	}
	return 99;
}

TEST(RunServer, EachRunIsAProcessOfItsOwnForkedByTheServer)
{
	const RunServer server(testEntry);
	ASSERT_TRUE(esif::runServerStarted());
	const auto result = runEsifChild({"esif", "whoami"}, ChildOutput::Kept, "test");
	EXPECT_EQ(result.exit_code, 7);
	pid_t pid = 0, parent = 0;
	ASSERT_EQ(std::sscanf(result.stderr_text.c_str(), "%d %d", &pid, &parent), 2) << result.stderr_text;
	EXPECT_NE(pid, getpid());
	EXPECT_NE(parent, getpid()) << "forked by the server's helper, not by this process";
}

TEST(RunServer, TheErrorLineAndTheKillingSignalComeBack)
{
	const RunServer server(testEntry);
	const auto failed = runEsifChild({"esif", "fail", "bad key"}, ChildOutput::Kept, "test");
	EXPECT_EQ(failed.exit_code, 1);
	EXPECT_EQ(failed.error_line, "esif: error: bad key");
	const auto killed = runEsifChild({"esif", "kill"}, ChildOutput::Kept, "test");
	EXPECT_EQ(killed.exit_code, 128 + SIGKILL);
	EXPECT_NE(killed.stderr_text.find("killed by signal 9"), std::string::npos) << killed.stderr_text;
}

TEST(RunServer, ConcurrentRunsKeepTheirOwnStderr)
{
	const RunServer server(testEntry);
	esif::ChildResult a, b;
	std::thread first([&] { a = runEsifChild({"esif", "echo", "first"}, ChildOutput::Kept, "test"); });
	std::thread second([&] { b = runEsifChild({"esif", "echo", "second"}, ChildOutput::Kept, "test"); });
	first.join();
	second.join();
	std::string expect_a, expect_b;
	for (int i = 0; i < 200; ++i) expect_a += "first\n", expect_b += "second\n";
	EXPECT_EQ(a.stderr_text, expect_a);
	EXPECT_EQ(b.stderr_text, expect_b);
}

TEST(RunServer, NoProcessOutlivesTheServer)
{
	// Orphans would become this process's children.
	ASSERT_EQ(::prctl(PR_SET_CHILD_SUBREAPER, 1), 0);
	{
		const RunServer server(testEntry);
		for (int i = 0; i < 3; ++i) EXPECT_EQ(runEsifChild({"esif", "whoami"}, ChildOutput::Kept, "test").exit_code, 7);
	}
	EXPECT_FALSE(esif::runServerStarted());
	int status = 0;
	EXPECT_EQ(::waitpid(-1, &status, WNOHANG), -1) << "a process of the server was left";
	EXPECT_EQ(errno, ECHILD);
	ASSERT_EQ(::prctl(PR_SET_CHILD_SUBREAPER, 0), 0);
}

}  // namespace
