// The replay loop with a fake plugin: every step's report is kept, a
// smoother's trajectory replaces the online poses (keyframes included) only
// when it has one pose per step, and a joining filter's final reports
// replace the online ones and are audited afresh.

#include <FakePlugin.h>
#include <FakeRawlog.h>

#include <EsifTestSupport.h>

#include <esif/formats/RawlogReader.h>
#include <esif/run/Replay.h>

#include <gtest/gtest.h>

namespace
{
using esif::Association;
using esif::test::FakePlugin;
using esif::test::makeRawlog;

const esif::ReplayOptions kQuiet{0, false};

/// Four steps: two scans, an odometry-only step, one more scan.
esif::Rawlog fourSteps() { return makeRawlog({{{7, std::nullopt}}, {{7}}, std::nullopt, {{8}}}); }

std::vector<esif::PoseEstimate> smoothedPoses(std::size_t n)
{
	std::vector<esif::PoseEstimate> poses(n);
	for (std::size_t k = 0; k < n; ++k) poses[k].mean = esif::Pose2(100 + static_cast<double>(k), -5, 0.5);
	return poses;
}

TEST(Replay, KeepsEveryStepsReport)
{
	FakePlugin plugin;
	const auto log = fourSteps();
	const auto result = esif::replay(plugin, log, kQuiet);
	ASSERT_EQ(result.reports.size(), 4u);
	ASSERT_EQ(result.reports[0].associations.size(), 2u);
	EXPECT_EQ(result.reports[0].associations[0].kind, Association::Kind::New);
	EXPECT_EQ(result.reports[0].associations[0].id, 7);
	EXPECT_EQ(result.reports[0].associations[1].kind, Association::Kind::Rejected);
	EXPECT_EQ(result.reports[1].associations[0].kind, Association::Kind::Matched);
	EXPECT_TRUE(result.reports[2].associations.empty());
	EXPECT_EQ(result.reports[3].associations[0].id, 8);
}

TEST(Replay, FilterKeepsOnlinePosesAndKeyframeSteps)
{
	FakePlugin plugin;
	const auto result = esif::replay(plugin, fourSteps(), kQuiet);
	ASSERT_EQ(result.record.trajectory.size(), 4u);
	EXPECT_DOUBLE_EQ(result.record.trajectory[3].pose.mean.x(), 4.0);  // dead reckoning, 1 m a step
	ASSERT_EQ(result.record.keyframes.size(), 3u);	// the steps with a sensory frame
	EXPECT_EQ(result.record.keyframes[0].step, 0u);
	EXPECT_EQ(result.record.keyframes[1].step, 1u);
	EXPECT_EQ(result.record.keyframes[2].step, 3u);
	EXPECT_DOUBLE_EQ(result.record.keyframes[2].pose.mean.x(), 4.0);
}

TEST(Replay, SmoothedTrajectoryReplacesPosesAndKeyframes)
{
	FakePlugin plugin;
	plugin.smoothed = smoothedPoses(4);
	(*plugin.smoothed)[3].cov = Eigen::Matrix3d::Identity() * 0.25;
	const auto result = esif::replay(plugin, fourSteps(), kQuiet);
	ASSERT_EQ(result.record.trajectory.size(), 4u);
	for (std::size_t k = 0; k < 4; ++k)
	{
		EXPECT_EQ(result.record.trajectory[k].step, k);
		EXPECT_DOUBLE_EQ(result.record.trajectory[k].pose.mean.x(), 100.0 + static_cast<double>(k));
		EXPECT_DOUBLE_EQ(result.record.trajectory[k].pose.mean.y(), -5.0);
	}
	EXPECT_DOUBLE_EQ(result.record.trajectory[3].pose.cov(2, 2), 0.25);
	ASSERT_EQ(result.record.keyframes.size(), 3u);
	for (const auto& kf : result.record.keyframes)
		EXPECT_DOUBLE_EQ(kf.pose.mean.x(), 100.0 + static_cast<double>(kf.step)) << "keyframe of step " << kf.step;
	EXPECT_DOUBLE_EQ(result.record.keyframes[2].pose.cov(2, 2), 0.25);
}

TEST(Replay, SmoothedTrajectoryOfWrongLengthNamesThePlugin)
{
	FakePlugin plugin;
	plugin.smoothed = smoothedPoses(3);
	try
	{
		esif::replay(plugin, fourSteps(), kQuiet);
		FAIL() << "expected std::logic_error";
	}
	catch (const std::logic_error& e)
	{
		const std::string what = e.what();
		EXPECT_NE(what.find("plugin esif::test::FakePlugin"), std::string::npos) << what;
		EXPECT_NE(what.find("smoothed trajectory of 3 poses for 4 steps"), std::string::npos) << what;
	}
}

/// The final reports of a joining filter for fourSteps(): landmark 7 became
/// global landmark 70 (its two sightings), 8 became 80; the rejected
/// measurement stays rejected.
std::vector<esif::StepReport> finalReportsOfFourSteps()
{
	return {{{{Association::Kind::New, 70}, {Association::Kind::Rejected, -1}}},
			{{{Association::Kind::Matched, 70}}},
			{},
			{{{Association::Kind::New, 80}}}};
}

TEST(Replay, FinalReportsReplaceTheOnlineOnesAndAreAuditedAgain)
{
	FakePlugin plugin;
	plugin.final_reports = finalReportsOfFourSteps();
	const auto result = esif::replay(plugin, fourSteps(), kQuiet);
	ASSERT_EQ(result.reports.size(), 4u);
	EXPECT_EQ(result.reports[0].associations[0].id, 70);
	EXPECT_EQ(result.reports[1].associations[0].kind, Association::Kind::Matched);
	EXPECT_EQ(result.reports[1].associations[0].id, 70);
	EXPECT_EQ(result.reports[3].associations[0].id, 80);
	// The audit maps the final IDs to the rawlog's, with nothing wrong.
	const auto to_true = result.audit.filterToTrue();
	ASSERT_EQ(to_true.size(), 2u);
	EXPECT_EQ(to_true.at(70), 7);
	EXPECT_EQ(to_true.at(80), 8);
	EXPECT_EQ(result.audit.newCount(), 2u);
	EXPECT_EQ(result.audit.matchedCount(), 1u);
	EXPECT_EQ(result.audit.rejectedCount(), 1u);
	EXPECT_EQ(result.audit.wrongCount(), 0u);
	// Landmark counts stay those of the online reports (7 new at step 0, 8 at step 3).
	EXPECT_EQ(result.landmark_counts, (std::vector<std::size_t>{1, 1, 1, 2}));
}

TEST(Replay, FinalReportsThatMergeTwoLandmarksAreScoredWrong)
{
	FakePlugin plugin;
	auto reports = finalReportsOfFourSteps();
	reports[3].associations[0] = {Association::Kind::Matched, 70};  // 8 fused into 7's landmark
	plugin.final_reports = reports;
	const auto result = esif::replay(plugin, fourSteps(), kQuiet);
	EXPECT_EQ(result.audit.filterToTrue().size(), 1u);
	EXPECT_EQ(result.audit.wrongCount(), 1u);
	EXPECT_EQ(result.audit.matchedCount(), 2u);
}

TEST(Replay, FinalReportsOfWrongShapeNameThePlugin)
{
	const auto expectLogicError = [](std::vector<esif::StepReport> reports, const std::string& expected) {
		FakePlugin plugin;
		plugin.final_reports = std::move(reports);
		try
		{
			esif::replay(plugin, fourSteps(), kQuiet);
			FAIL() << "expected std::logic_error";
		}
		catch (const std::logic_error& e)
		{
			const std::string what = e.what();
			EXPECT_NE(what.find("plugin esif::test::FakePlugin"), std::string::npos) << what;
			EXPECT_NE(what.find(expected), std::string::npos) << what;
		}
	};
	auto short_list = finalReportsOfFourSteps();
	short_list.pop_back();
	expectLogicError(short_list, "3 final reports for 4 steps");
	auto short_step = finalReportsOfFourSteps();
	short_step[0].associations.pop_back();
	expectLogicError(short_step, "final report of 1 associations for 2 measurements at step 0");
}

/// Reads grid196 keeping its steps or leaving them in the file.
esif::Rawlog grid196(bool keep_steps)
{
	esif::RawlogReadOptions options;
	options.keep_steps = keep_steps;
	return esif::readRawlog(esif::test::sourcePath("rawlogs/grid196.rawlog"), options);
}

/// Every step's report and pose, and the audit, of two replays.
void expectSameReplay(const esif::ReplayResult& a, const esif::ReplayResult& b)
{
	ASSERT_EQ(a.reports.size(), b.reports.size());
	for (std::size_t k = 0; k < a.reports.size(); ++k)
	{
		ASSERT_EQ(a.reports[k].associations.size(), b.reports[k].associations.size()) << "step " << k;
		for (std::size_t i = 0; i < a.reports[k].associations.size(); ++i)
		{
			EXPECT_EQ(a.reports[k].associations[i].kind, b.reports[k].associations[i].kind);
			EXPECT_EQ(a.reports[k].associations[i].id, b.reports[k].associations[i].id);
		}
		EXPECT_EQ(a.record.trajectory[k].pose.mean, b.record.trajectory[k].pose.mean) << "step " << k;
		EXPECT_EQ(a.record.trajectory[k].time_s, b.record.trajectory[k].time_s) << "step " << k;
	}
	EXPECT_EQ(a.record.keyframes.size(), b.record.keyframes.size());
	EXPECT_EQ(a.audit.matchedCount(), b.audit.matchedCount());
	EXPECT_EQ(a.audit.wrongCount(), b.audit.wrongCount());
	EXPECT_EQ(a.ospa_cutoff_m, b.ospa_cutoff_m);
}

TEST(Replay, StepsReadAgainFromTheFileReplayAsStepsKept)
{
	FakePlugin kept_plugin, lean_plugin;
	const esif::Rawlog kept = grid196(true), lean = grid196(false);
	ASSERT_TRUE(lean.stepsLeftInFile());
	const auto a = esif::replay(kept_plugin, kept, kQuiet);
	const auto b = esif::replay(lean_plugin, lean, kQuiet);
	ASSERT_EQ(b.reports.size(), kept.steps.size());
	expectSameReplay(a, b);
	EXPECT_TRUE(a.ospa_cutoff_m.has_value());
}

TEST(Replay, EachStepIsPreparedBeforeThePluginSeesIt)
{
	// Every measurement's ID taken away: the fake plugin then rejects them all.
	esif::ReplayOptions options(0, false);
	std::size_t prepared = 0;
	options.prepare = [&prepared](esif::StepInput& step) {
		++prepared;
		if (step.scan)
			for (auto& m : step.scan->measurements) m.id.reset();
	};
	for (const bool keep : {true, false})
	{
		FakePlugin plugin;
		prepared = 0;
		const esif::Rawlog log = grid196(keep);
		const auto result = esif::replay(plugin, log, options);
		EXPECT_EQ(prepared, log.stepCount()) << "keep_steps " << keep;
		EXPECT_EQ(result.audit.matchedCount(), 0u) << "keep_steps " << keep;
		if (keep)
		{
			EXPECT_TRUE(log.steps[1].scan->measurements[0].id) << "the kept steps stay as read";
		}
	}
}

}  // namespace
