// A read that leaves the steps in the file (RawlogReadOptions::keep_steps
// off) keeps everything else a full read keeps, and the steps read again one
// at a time (RawlogSteps.h) are the steps a full read keeps, field by field;
// a rawlog replaced since it was read is refused rather than replayed.

#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/formats/RawlogReader.h>
#include <esif/formats/RawlogSteps.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace
{
using namespace esif;
namespace fs = std::filesystem;

RawlogReadOptions leaving(RawlogReadOptions options = {})
{
	options.keep_steps = false;
	return options;
}

void expectSameStep(const StepInput& again, const StepInput& kept)
{
	EXPECT_EQ(again.index, kept.index);
	EXPECT_EQ(again.time_s, kept.time_s);
	ASSERT_EQ(again.odometry.has_value(), kept.odometry.has_value());
	if (kept.odometry)
	{
		EXPECT_EQ(again.odometry->delta, kept.odometry->delta);
		EXPECT_EQ(again.odometry->cov, kept.odometry->cov);
	}
	ASSERT_EQ(again.scan.has_value(), kept.scan.has_value());
	if (!kept.scan) return;
	EXPECT_EQ(again.scan->sensor_on_robot, kept.scan->sensor_on_robot);
	EXPECT_EQ(again.scan->max_range_m, kept.scan->max_range_m);
	EXPECT_EQ(again.scan->fov_rad, kept.scan->fov_rad);
	ASSERT_EQ(again.scan->measurements.size(), kept.scan->measurements.size());
	for (std::size_t i = 0; i < kept.scan->measurements.size(); ++i)
	{
		const RangeBearing &a = again.scan->measurements[i], &b = kept.scan->measurements[i];
		EXPECT_EQ(a.range_m, b.range_m);
		EXPECT_EQ(a.bearing_rad, b.bearing_rad);
		EXPECT_EQ(a.id, b.id);
		EXPECT_EQ(a.cov, b.cov);
	}
}

/// Every step of `lean`'s file read again, against `kept`.
void expectStepsReadAgainAreKept(const Rawlog& lean, const Rawlog& kept)
{
	ASSERT_TRUE(lean.stepsLeftInFile());
	RawlogStepStream stream(*lean.source, "test");
	for (std::size_t k = 0; k < kept.steps.size(); ++k)
	{
		ASSERT_EQ(stream.given(), k);
		const RawlogStep& step = stream.next();
		expectSameStep(step.input, kept.steps[k]);
		EXPECT_EQ(step.ids, kept.true_ids[k]) << "step " << k;
		EXPECT_EQ(step.frame != nullptr, kept.steps[k].scan.has_value()) << "step " << k;
		if (::testing::Test::HasFailure()) FAIL() << "first difference at step " << k;
	}
	EXPECT_NO_THROW(stream.finish());
}

TEST(RawlogSteps, ALeanReadKeepsEverythingButTheSteps)
{
	const std::string rawlog = test::sourcePath("rawlogs/grid196.rawlog");
	const Rawlog kept = readRawlog(rawlog), lean = readRawlog(rawlog, leaving());
	EXPECT_TRUE(lean.steps.empty());
	EXPECT_TRUE(lean.frames.empty());
	EXPECT_FALSE(kept.stepsLeftInFile());
	EXPECT_EQ(lean.stepCount(), kept.steps.size());
	EXPECT_EQ(lean.true_ids, kept.true_ids);
	EXPECT_EQ(lean.measurement_count, kept.measurement_count);
	EXPECT_EQ(lean.has_odometry, kept.has_odometry);
	EXPECT_TRUE(lean.any_landmark_id);
	EXPECT_EQ(lean.any_landmark_id, kept.any_landmark_id);
	EXPECT_EQ(lean.source->steps_digest, kept.source->steps_digest);
}

TEST(RawlogSteps, StepsReadAgainAreTheStepsAFullReadKeeps)
{
	const std::string rawlog = test::sourcePath("rawlogs/grid196.rawlog");
	expectStepsReadAgainAreKept(readRawlog(rawlog, leaving()), readRawlog(rawlog));
}

TEST(RawlogSteps, HiddenIdsStayHiddenWhenReadAgain)
{
	RawlogReadOptions hidden;
	hidden.hide_landmark_ids = true;
	const std::string rawlog = test::sourcePath("rawlogs/grid196.rawlog");
	const Rawlog lean = readRawlog(rawlog, leaving(hidden));
	EXPECT_FALSE(lean.any_landmark_id);
	expectStepsReadAgainAreKept(lean, readRawlog(rawlog, hidden));
}

TEST(RawlogSteps, ARawlogReplacedSinceItWasReadIsRefused)
{
	test::TempDir dir;
	const std::string rawlog = dir.file("log.rawlog");
	fs::copy_file(test::sourcePath("rawlogs/grid196.rawlog"), rawlog);
	const Rawlog lean = readRawlog(rawlog, leaving());
	const std::string bytes = test::readText(rawlog);
	fs::remove(rawlog);
	std::ofstream(rawlog, std::ios::binary) << bytes;
	try
	{
		RawlogStepStream stream(*lean.source, "the replay reads its steps from it");
		FAIL() << "no error";
	}
	catch (const InputError& e)
	{
		EXPECT_EQ(std::string(e.what()),
				  rawlog + ": replaced or modified since esif read it; the replay reads its steps from it: run again");
	}
}

TEST(RawlogSteps, AStreamEndedBeforeItsLastStepIsAnError)
{
	const Rawlog lean = readRawlog(test::sourcePath("rawlogs/grid196.rawlog"), leaving());
	RawlogStepStream stream(*lean.source, "test");
	stream.next();
	EXPECT_THROW(stream.finish(), InputError);
}
}  // namespace
