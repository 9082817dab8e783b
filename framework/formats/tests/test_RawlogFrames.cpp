// A replay that does not keep the log's sensory frames writes map.simplemap
// from a second pass over the rawlog (RawlogFrames.h): the frames read again
// are those a full read keeps, the map is the same file byte for byte, and a
// rawlog changed since it was read is refused rather than mixed in.

#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/formats/MapWriter.h>
#include <esif/formats/RawlogFrames.h>
#include <esif/formats/RawlogReader.h>

#include <mrpt/io/CMemoryStream.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/serialization/CArchive.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace
{
using namespace esif;
namespace fs = std::filesystem;

std::string bytesOf(const mrpt::serialization::CSerializable& object)
{
	mrpt::io::CMemoryStream stream;
	auto archive = mrpt::serialization::archiveFrom(stream);
	archive << object;
	return {static_cast<const char*>(stream.getRawBufferData()), static_cast<std::size_t>(stream.getTotalBytesCount())};
}

std::string inflated(const std::string& path)
{
	mrpt::io::CFileGZInputStream in(path);
	std::string out, chunk(1 << 16, '\0');
	for (std::size_t n; (n = in.Read(chunk.data(), chunk.size())) > 0;) out.append(chunk, 0, n);
	return out;
}

RawlogReadOptions withoutFrames()
{
	RawlogReadOptions options;
	options.keep_frames = false;
	return options;
}

/// Every fifth step with a scan of `log` as a keyframe at a pose of its own.
RunRecord keyframesOf(const Rawlog& log)
{
	RunRecord run;
	run.frames_source = log.source;
	for (std::size_t k = 0; k < log.steps.size(); k += 5)
		if (log.steps[k].scan)
			run.keyframes.push_back({{Pose2(0.1 * k, -0.2 * k, 0.01 * k), 1e-3 * Eigen::Matrix3d::Identity()},
									 log.frames[k], k});
	return run;
}

TEST(RawlogFrames, FramesReadAgainAreTheFramesAFullReadKeeps)
{
	const std::string rawlog = test::sourcePath("rawlogs/grid196.rawlog");
	const Rawlog kept = readRawlog(rawlog), lean = readRawlog(rawlog, withoutFrames());
	ASSERT_EQ(lean.steps.size(), kept.steps.size());
	for (const auto& frame : lean.frames) EXPECT_EQ(frame, nullptr);
	ASSERT_TRUE(lean.source);
	std::vector<std::size_t> steps;
	for (std::size_t k = 3; k < kept.steps.size(); k += 97)
		if (kept.steps[k].scan) steps.push_back(k);
	ASSERT_GT(steps.size(), 20u);
	std::size_t next = 0;
	readFramesAgain(*lean.source, steps, [&](std::size_t step, const mrpt::obs::CSensoryFrame::Ptr& frame) {
		ASSERT_LT(next, steps.size());
		EXPECT_EQ(step, steps[next]);
		EXPECT_EQ(bytesOf(*frame), bytesOf(*kept.frames[step])) << "step " << step;
		++next;
	});
	EXPECT_EQ(next, steps.size());
}

TEST(RawlogFrames, TheSimpleMapWrittenFromTheFileIsTheSimpleMapOfKeptFrames)
{
	test::TempDir dir;
	const std::string rawlog = test::sourcePath("rawlogs/grid196.rawlog");
	RunRecord from_memory = keyframesOf(readRawlog(rawlog));
	from_memory.frames_source.reset();
	const RunRecord from_file = keyframesOf(readRawlog(rawlog, withoutFrames()));
	ASSERT_EQ(from_file.keyframes.size(), from_memory.keyframes.size());
	ASSERT_EQ(from_file.keyframes.front().frame, nullptr);
	writeSimpleMap(from_memory, dir.file("memory.simplemap"));
	writeSimpleMap(from_file, dir.file("file.simplemap"));
	EXPECT_EQ(inflated(dir.file("file.simplemap")), inflated(dir.file("memory.simplemap")));
}

TEST(RawlogFrames, ARawlogChangedSinceItWasReadIsRefusedAndNoMapIsWritten)
{
	test::TempDir dir;
	const std::string rawlog = dir.file("log.rawlog");
	fs::copy_file(test::sourcePath("rawlogs/grid196.rawlog"), rawlog);
	const RunRecord run = keyframesOf(readRawlog(rawlog, withoutFrames()));
	// Replaced by another recording (here: the same bytes, rewritten).
	const std::string bytes = test::readText(rawlog);
	fs::remove(rawlog);
	std::ofstream(rawlog, std::ios::binary) << bytes;
	try
	{
		writeSimpleMap(run, dir.file("map.simplemap"));
		FAIL() << "no error";
	}
	catch (const InputError& e)
	{
		EXPECT_EQ(std::string(e.what()), rawlog + ": replaced or modified since esif read it; map.simplemap needs its "
												"sensory frames: run again");
	}
	EXPECT_FALSE(fs::exists(dir.file("map.simplemap")));
}

TEST(RawlogFrames, AStepBeyondTheLogIsAnError)
{
	const Rawlog log = readRawlog(test::sourcePath("rawlogs/grid196.rawlog"), withoutFrames());
	const auto none = [](std::size_t, const mrpt::obs::CSensoryFrame::Ptr&) {};
	EXPECT_THROW(readFramesAgain(*log.source, {log.steps.size()}, none), InputError);
}
}  // namespace
