// Hostile rawlogs: every class of issue 15's findings on the reader gives
// one InputError line naming the file and entry, in bounded memory, and
// never a crash. Inputs are built here from valid MRPT objects and then
// damaged, so no third-party file is needed.

#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/formats/RawlogReader.h>

#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <gtest/gtest.h>
#include <iostream>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sys/resource.h>
#include <zlib.h>

namespace
{
using namespace esif;
using namespace mrpt::obs;

/// One odometry action as MRPT's own rawlog grabbers write it: the default
/// emOdometry method, whose pose PDF MRPT rebuilds from the motion model.
CActionCollection odometryAction()
{
	CActionRobotMovement2D mv;
	CActionRobotMovement2D::TMotionModelOptions model;
	mv.computeFromOdometry(mrpt::poses::CPose2D(0.1, 0, 0.01), model);
	CActionCollection acts;
	acts.insert(mv);
	return acts;
}

CSensoryFrame frameWith(std::size_t measurements)
{
	auto obs = CObservationBearingRange::Create();
	obs->sensor_std_range = 0.1f;
	obs->sensor_std_yaw = 0.01f;
	obs->maxSensorDistance = 5;
	obs->fieldOfView_yaw = M_PI;
	for (std::size_t i = 0; i < measurements; ++i)
	{
		CObservationBearingRange::TMeasurement m;
		m.range = 1.0f + 0.001f * static_cast<float>(i);
		m.yaw = 0.1f;
		m.pitch = 0;
		m.landmarkID = static_cast<int32_t>(i);
		obs->sensedData.push_back(m);
	}
	CSensoryFrame sf;
	sf.insert(obs);
	return sf;
}

/// An inflated rawlog of `steps` (action, frame) pairs.
std::string rawlogBytes(int steps, std::size_t measurements = 2)
{
	mrpt::io::CMemoryStream mem;
	auto ar = mrpt::serialization::archiveFrom(mem);
	for (int k = 0; k < steps; ++k) ar << odometryAction() << frameWith(measurements);
	return std::string(static_cast<const char*>(mem.getRawBufferData()), mem.getTotalBytesCount());
}

/// The reader's verdict on `bytes`: "" when it reads them, else its error.
std::string verdictOn(const std::string& bytes, const RawlogReadOptions& options = {})
{
	try
	{
		readRawlogFromMemory("hostile.rawlog", bytes, options);
		return "";
	}
	catch (const InputError& e)
	{
		return e.what();
	}
}

void expectOneLineNamingTheFile(const std::string& message)
{
	EXPECT_EQ(message.find('\n'), std::string::npos) << message;
	EXPECT_EQ(message.rfind("hostile.rawlog: ", 0), 0u) << message;
}

void writeGzip(const std::string& path, const std::string& bytes)
{
	gzFile f = gzopen(path.c_str(), "wb6");
	ASSERT_NE(f, nullptr);
	ASSERT_EQ(gzwrite(f, bytes.data(), static_cast<unsigned>(bytes.size())), static_cast<int>(bytes.size()));
	ASSERT_EQ(gzclose(f), Z_OK);
}

void writeFile(const std::string& path, const std::string& bytes)
{
	std::ofstream(path, std::ios::binary) << bytes;
}

std::string errorOf(const std::string& path)
{
	try
	{
		readRawlog(path);
		return "";
	}
	catch (const InputError& e)
	{
		return e.what();
	}
}
/// MRPT reads a value cut by the end of the data partly (CArchive's
/// operator>> ignores a short read): a CObservationBearingRange cut inside
/// its measurement count left three bytes of it uninitialised, so the
/// sandboxed read and the one after it disagreed, and one file gave three
/// outcomes over ten runs (exit 1, exit 4 bad_alloc, a warning). Cut at
/// every byte of the last frame, each file now reads the same way every
/// time, as a file cut there: a warning and the steps before the cut.
TEST(RawlogReaderHostile, ACutInsideAValueReadsTheSameEveryTime)
{
	const std::string whole = rawlogBytes(3) + rawlogBytes(1, 5);
	// The last frame (its five measurements and their count among them).
	const std::size_t frame_bytes = rawlogBytes(1, 5).size() - rawlogBytes(1, 0).size() + 40;
	for (std::size_t cut = whole.size() - frame_bytes; cut < whole.size(); ++cut)
	{
		const std::string bytes = whole.substr(0, cut);
		std::string first;
		for (int i = 0; i < 2; ++i)
		{
			std::string answer;
			try
			{
				const Rawlog log = readRawlogFromMemory("hostile.rawlog", bytes);
				answer = std::to_string(log.steps.size()) + " steps; " + log.truncation_warning.value_or("no warning");
			}
			catch (const InputError& e)
			{
				answer = e.what();
				expectOneLineNamingTheFile(answer);
			}
			if (i == 0)
				first = answer;
			else
				EXPECT_EQ(answer, first) << "cut at " << cut << " of " << whole.size();
		}
		// Whatever value the cut lands in, the file reads as cut there.
		EXPECT_EQ(first, "3 steps; hostile.rawlog: file ends inside entry 7; read up to step 3") << "cut at " << cut;
	}

	// The fuzzer's case: one byte of the count, the rest of it left to what
	// lay on the stack. In one process that is the same every time; across
	// processes it held parts of (randomised) addresses, so esif gave
	// different answers run after run. Each run here is a process of its own.
	const std::string five = rawlogBytes(3) + rawlogBytes(1, 5);
	// The count (uint32 5) and the first measurement's range (float 1.0), little-endian.
	const std::size_t count_at = five.rfind(std::string("\x05\0\0\0\0\0\x80\x3f", 8));
	ASSERT_NE(count_at, std::string::npos);
	test::TempDir dir;
	std::ofstream(dir.file("cut.rawlog"), std::ios::binary) << five.substr(0, count_at + 1);
	std::ofstream(dir.file("ekf.ini")) << "[esif]\nplugin = EkfSlam\n";
	std::set<std::string> outcomes;
	for (int i = 0; i < 8; ++i)
	{
		const auto r = test::runEsif("run -q --no-figures --config '" + dir.file("ekf.ini") + "' --rawlog '" +
									 dir.file("cut.rawlog") + "' --out '" + dir.file("o" + std::to_string(i)) + "'");
		outcomes.insert(std::to_string(r.exit_code) + " " + r.out);
	}
	ASSERT_EQ(outcomes.size(), 1u) << *outcomes.begin() << "\n" << *outcomes.rbegin();
	EXPECT_EQ(*outcomes.begin(), "0 esif: warning: " + dir.file("cut.rawlog") +
									 ": file ends inside entry 7; read up to step 3\n");
}

}  // namespace

// Issue 15, finding 1, as a class: every single-byte change of a one-step
// log (each byte + 1, which includes the estimationMethod 0 -> 1) is
// read or refused in one line; none may end the test process. MRPT's own
// null dereference on the changed method must be among the refusals.
TEST(RawlogReaderHostile, EverySingleByteChangeIsReadOrRefusedInOneLine)
{
	const std::string valid = rawlogBytes(1);
	std::cout << valid.size() << " bytes, one sandboxed read per byte\n";
	ASSERT_EQ(verdictOn(valid), "");
	int refused = 0, crashes_contained = 0;
	for (std::size_t i = 0; i < valid.size(); ++i)
	{
		std::string bytes = valid;
		bytes[i] = static_cast<char>(bytes[i] + 1);
		const std::string verdict = verdictOn(bytes);
		if (verdict.empty()) continue;
		++refused;
		expectOneLineNamingTheFile(verdict);
		if (verdict.find("MRPT's deserialiser crashed") != std::string::npos) ++crashes_contained;
	}
	EXPECT_GT(refused, 0);
	EXPECT_GT(crashes_contained, 0) << "the estimationMethod change no longer reaches MRPT's null dereference";
}

// Finding 2: a count declared far beyond the file (2.5e9 observations in a
// 200-byte frame) is refused without the memory it declares: the sandboxed
// child may map at most 256 MiB + 64 bytes per file byte.
TEST(RawlogReaderHostile, DeclaredCountsBeyondTheFileAreRefusedInBoundedMemory)
{
	const std::string valid = rawlogBytes(1, 1);
	int over_budget = 0;
	// Plant 2.5e9 (little-endian) at every offset: one of them is the
	// frame's observation count, others hit other lengths.
	const unsigned char huge[4] = {0x00, 0xF9, 0x02, 0x95};
	for (std::size_t i = 0; i + 4 <= valid.size(); ++i)
	{
		std::string bytes = valid;
		for (int b = 0; b < 4; ++b) bytes[i + b] = static_cast<char>(huge[b]);
		const std::string verdict = verdictOn(bytes);
		if (verdict.empty()) continue;
		expectOneLineNamingTheFile(verdict);
		if (verdict.find("declares more data than the file holds") != std::string::npos) ++over_budget;
	}
	EXPECT_GT(over_budget, 0);
	rusage usage{};
	getrusage(RUSAGE_CHILDREN, &usage);
	// ru_maxrss is in KiB: no sandboxed read may have touched more than its budget.
	EXPECT_LT(usage.ru_maxrss, (256 + 64) * 1024L) << "a reader child grew to " << usage.ru_maxrss / 1024 << " MiB";
}

// Finding 2: one scan of 100,000 measurements is refused by the cap, which
// is a parameter.
TEST(RawlogReaderHostile, MeasurementsPerScanAreCapped)
{
	const std::string bytes = rawlogBytes(1, 1001);
	const std::string verdict = verdictOn(bytes);
	expectOneLineNamingTheFile(verdict);
	EXPECT_NE(verdict.find("entry 1: one scan holds 1001 measurements, more than max_measurements_per_scan = 1000"),
			  std::string::npos)
		<< verdict;
	RawlogReadOptions options;
	options.max_measurements_per_scan = 2000;
	EXPECT_EQ(verdictOn(bytes, options), "");
}

// Finding 5: gzip damage is an error (CRC), empty files say so, and a cut
// gzip stream is read up to the cut with a warning.
TEST(RawlogReaderHostile, GzipStreamsAreCheckedBeforeMrptReadsThem)
{
	test::TempDir dir;
	const std::string valid = rawlogBytes(30);
	const std::string gz = dir.file("log.rawlog");
	writeGzip(gz, valid);
	ASSERT_EQ(errorOf(gz), "");
	const std::string packed = test::readText(gz);

	std::string bad_crc = packed;
	bad_crc[bad_crc.size() - 6] ^= 0x01;  // gzip trailer: CRC32, then the size
	writeFile(dir.file("crc.rawlog"), bad_crc);
	EXPECT_NE(errorOf(dir.file("crc.rawlog")).find("crc.rawlog: gzip data is corrupt"), std::string::npos)
		<< errorOf(dir.file("crc.rawlog"));

	writeFile(dir.file("empty.rawlog"), "");
	EXPECT_EQ(errorOf(dir.file("empty.rawlog")), dir.file("empty.rawlog") + ": file is empty");

	writeFile(dir.file("header.rawlog"), packed.substr(0, 10));
	EXPECT_NE(errorOf(dir.file("header.rawlog")).find("gzip stream is cut before its first byte"), std::string::npos)
		<< errorOf(dir.file("header.rawlog"));

	// Cut inside the last deflate bytes: identical steps compress to back
	// references, so only a cut near the end leaves most of them readable.
	writeFile(dir.file("cut.rawlog"), packed.substr(0, packed.size() - 20));
	const Rawlog cut = readRawlog(dir.file("cut.rawlog"));
	ASSERT_TRUE(cut.truncation_warning);
	EXPECT_GT(cut.steps.size(), 15u);
	EXPECT_LT(cut.steps.size(), 30u);
}

// Finding 5: bytes that stop in the middle of the file without running out
// are a corrupt entry, named, not a silent end of the log.
TEST(RawlogReaderHostile, GarbageInTheMiddleIsACorruptEntryNotATruncation)
{
	std::string bytes = rawlogBytes(10);
	const std::string tail = bytes.substr(bytes.size() / 2);
	bytes = bytes.substr(0, bytes.size() / 2) + std::string(64, '\x77') + tail;
	const std::string verdict = verdictOn(bytes);
	expectOneLineNamingTheFile(verdict);
	EXPECT_NE(verdict.find(" is corrupt"), std::string::npos) << verdict;
}

// Finding 1 end to end: `esif run` on a log whose first action makes MRPT's
// deserialiser dereference null exits 1 with one line naming file and entry
// (it used to die by SIGSEGV, exit 139, with no message).
TEST(RawlogReaderHostile, EsifRunReportsADeserialiserCrashInOneLine)
{
	const std::string valid = rawlogBytes(3);
	std::string crashing;
	for (std::size_t i = 0; i < valid.size() && crashing.empty(); ++i)
	{
		std::string bytes = valid;
		bytes[i] = static_cast<char>(bytes[i] + 1);
		if (verdictOn(bytes).find("MRPT's deserialiser crashed") != std::string::npos) crashing = bytes;
	}
	ASSERT_FALSE(crashing.empty());
	test::TempDir dir;
	writeFile(dir.file("crash.rawlog"), crashing);
	const auto r = test::runEsif("run --config '" + test::sourcePath("configs/ekf.ini") + "' --rawlog '" +
								 dir.file("crash.rawlog") + "' --out '" + dir.file("out") + "' --quiet");
	EXPECT_EQ(r.exit_code, 1) << r.out;
	EXPECT_EQ(r.out.rfind("esif: error: " + dir.file("crash.rawlog") + ": entry 0 is corrupt: MRPT's deserialiser crashed", 0), 0u)
		<< r.out;
	EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
	EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}
