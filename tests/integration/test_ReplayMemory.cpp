// A long log is replayed within a memory limit: the replay holds neither the
// log's steps nor its MRPT sensory frames; it reads the steps again from the
// rawlog one at a time (RawlogSteps.h), and map.simplemap the keyframes'
// frames (RawlogFrames.h).
//
// The limit: this 150,000-step log (1.8 measurements per scan) was measured
// with prlimit bisection (RLIMIT_AS, 50 MiB steps) to need 550-600 MiB of
// address space with the steps read again, 600-650 MiB with every step kept,
// and 850-900 MiB with every step's frame kept too. 750 MiB leaves at least
// 150 MiB.

#include <ChildProcess.h>
#include <EsifTestSupport.h>

#include <mrpt/maps/CSimpleMap.h>

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <utility>

namespace
{
using esif::test::sourcePath;
using esif::test::TempDir;

/// A 150,000-step tour of a 20 m square (1 m/s, at most 45 deg/s),
/// simulated into DIR/NAME.rawlog; `world` gives the features and sensor.
std::string simulatedTour(const TempDir& dir, const std::string& name, const std::string& world)
{
	const auto r = esif::test::simulateScenario(
		dir, name,
		"seed = 1\nworld_size_m = 20\ndt_s = 0.1\nsteps = 150000\nspeed_mps = 1.0\nmax_turn_rate_deg_s = 45\n"
		"waypoint_margin_m = 3\n" +
			world);
	EXPECT_EQ(r.exit_code, 0) << r.out;
	return dir.file(name + ".rawlog");
}

/// `esif run` of the EKF on `rawlog` into DIR/run within 750 MiB of address
/// space: its exit code and output.
std::pair<int, std::string> runEkfWithin750MiB(const TempDir& dir, const std::string& rawlog)
{
	return esif::test::finish(esif::test::spawnEsif(
		{"run", "-q", "--no-figures", "--config", sourcePath("configs/ekf.ini"), "--rawlog", rawlog, "--out",
		 dir.file("run")},
		esif::test::SpawnLimits{{}, rlim_t{750} << 20, {}}));
}
}  // namespace

TEST(ReplayMemory, ALongLogIsReplayedWithinALimitItsSensoryFramesWouldExceed)
{
	TempDir dir;
	// 100 features in a 20 m square, a 3 m 90-degree sensor: few measurements
	// per scan, so the frames (about 1 kB each) outweigh the rest of the log.
	const std::string rawlog =
		simulatedTour(dir, "long", "features_per_side = 10\nsensor_max_range_m = 3\nsensor_fov_deg = 90\n");
	ASSERT_FALSE(::testing::Test::HasFailure());
	const auto [code, text] = runEkfWithin750MiB(dir, rawlog);
	ASSERT_EQ(code, 0) << text;

	// Every scan is a keyframe (keyframe_min_distance_m = 0), each with its frame.
	mrpt::maps::CSimpleMap map;
	ASSERT_TRUE(map.loadFromFile(dir.file("run/map.simplemap")));
	EXPECT_EQ(map.size(), 150000u);
	std::size_t observations = 0;
	for (std::size_t i = 0; i < map.size(); i += 1000) observations += std::get<1>(map.get(i))->size();
	EXPECT_GT(observations, 0u);
}

TEST(ReplayMemory, ALogOfManyMeasurementsIsReplayedWithoutHoldingItsSteps)
{
	// 16 features all in view (40 m range, 360 degrees): 16 measurements on
	// every one of 150,000 scans, 2.4 million in all, so the steps themselves
	// are the larger part of the log. Measured with prlimit bisection
	// (RLIMIT_AS) on this log: 650-675 MiB with the steps read again one at a
	// time, 825-850 MiB with every step kept (as before); peak RSS 398 against
	// 568 MB. 750 MiB leaves 75 MiB either way: a replay that held the steps
	// again would fail here.
	TempDir dir;
	const std::string rawlog =
		simulatedTour(dir, "dense", "features_per_side = 4\nsensor_max_range_m = 40\nsensor_fov_deg = 360\n");
	ASSERT_FALSE(::testing::Test::HasFailure());
	const auto [code, text] = runEkfWithin750MiB(dir, rawlog);
	ASSERT_EQ(code, 0) << text;
	// Every measurement was replayed: associations.txt has a row for each.
	std::ifstream associations(dir.file("run/associations.txt"));
	std::size_t rows = 0;
	for (std::string line; std::getline(associations, line);) rows += !line.empty() && line[0] != '#';
	EXPECT_EQ(rows, 2400000u);
}

