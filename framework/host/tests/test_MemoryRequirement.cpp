/// \file test_MemoryRequirement.cpp
/// The host refuses, before the replay, a plugin whose dense estimate of
/// the log's landmarks would not fit the memory this process may use.

#include <esif/core/Errors.h>
#include <esif/run/MemoryRequirement.h>

#include "FakePlugin.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace esif;

namespace
{
/// A log of `scans` scans of the landmarks `ids` (IDs as the file has them).
Rawlog logOf(const std::vector<std::vector<LandmarkId>>& scans)
{
	Rawlog log;
	log.path = "l.rawlog";
	for (const auto& ids : scans)
	{
		StepInput step;
		Scan scan;
		std::vector<std::optional<LandmarkId>> truth;
		for (const LandmarkId id : ids)
		{
			RangeBearing m;
			m.range_m = 1;
			m.id = id;
			scan.measurements.push_back(m);
			truth.push_back(id);
		}
		step.scan = scan;
		log.steps.push_back(step);
		log.true_ids.push_back(truth);
	}
	return log;
}
}  // namespace

TEST(MemoryRequirement, LandmarksAreTheDistinctTrueIdsEvenWhenHidden)
{
	Rawlog log = logOf({{1, 2, 3}, {3, 4}, {}});
	EXPECT_EQ(landmarksInLog(log), 4u);
	// Hidden from the plugin (hide_landmark_ids): the true IDs still count.
	for (auto& step : log.steps)
		for (auto& m : step.scan->measurements) m.id.reset();
	EXPECT_EQ(landmarksInLog(log), 4u);
	// No ID anywhere: the log does not say.
	for (auto& ids : log.true_ids)
		for (auto& id : ids) id.reset();
	EXPECT_EQ(landmarksInLog(log), std::nullopt);
}

TEST(MemoryRequirement, ADenseEstimateBeyondTheBudgetIsRefusedInOneLine)
{
	const Rawlog log = logOf({{1, 2, 3, 4}});
	test::FakePlugin plugin;
	const MemoryBudget budget{1000, "RLIMIT_AS"};
	EXPECT_NO_THROW(requireMemory(plugin, log, "c.ini", budget)) << "no memory model: never refused";
	plugin.bytes_per_landmark = 250;  // 4 landmarks: exactly the budget
	EXPECT_NO_THROW(requireMemory(plugin, log, "c.ini", budget));
	plugin.bytes_per_landmark = 1024.0 * 1024 * 1024;
	try
	{
		requireMemory(plugin, log, "c.ini", budget);
		FAIL() << "not refused";
	}
	catch (const ConfigError& e)
	{
		EXPECT_EQ(std::string(e.what()),
				  "c.ini: plugin test::FakePlugin would need 4 GiB for its estimate of the 4 landmarks of l.rawlog, "
				  "more than the 9.31e-07 GiB this process may use (RLIMIT_AS): choose a sparse information filter "
				  "for a map this size");
	}
}

TEST(MemoryRequirement, TheBudgetIsTheSmallestLimit)
{
	const rlim_t limit = 900u << 20;
	const MemoryBudget unlimited = memoryBudget();
	EXPECT_GT(unlimited.bytes, 64.0 * 1024 * 1024);
	if (unlimited.bytes <= static_cast<double>(limit)) GTEST_SKIP() << "this machine gives less than 900 MiB already";
	// In a child, so the limit does not outlive the test.
	const pid_t pid = ::fork();
	if (pid == 0)
	{
		const rlimit as{limit, RLIM_INFINITY};
		::setrlimit(RLIMIT_AS, &as);
		const MemoryBudget b = memoryBudget();
		::_exit(b.bytes == static_cast<double>(limit) && b.set_by == "RLIMIT_AS" ? 0 : 1);
	}
	int status = 0;
	::waitpid(pid, &status, 0);
	EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}
