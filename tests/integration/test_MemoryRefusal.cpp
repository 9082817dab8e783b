// A plugin whose estimate is one dense matrix (the EKF's covariance) is
// refused before the replay when the map of the rawlog would not fit the
// memory the process may use: one line naming what it would need, exit 1,
// no output folder, instead of an out-of-memory failure hours into the run.

#include <ChildProcess.h>
#include <EsifTestSupport.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using esif::test::sourcePath;
using esif::test::TempDir;

TEST(MemoryRefusal, TheEkfOnAMapTooLargeForTheLimitIsRefusedBeforeItStarts)
{
	// 9,229 landmarks in 12 scans (a 17 m all-round sensor over a 1 m grid):
	// the EKF's covariance would be (3 + 2 x 9229)^2 doubles, 2.54 GiB,
	// against a 600 MiB address space, in which esif itself runs
	// (test_hostile_inputs runs the EKF under the same limit).
	TempDir dir;
	const auto simulated = esif::test::simulateScenario(
		dir, "dense",
		"seed = 1\nworld_size_m = 300\nfeatures_per_side = 300\ndt_s = 3\nsteps = 12\nspeed_mps = 10\n"
		"sensor_max_range_m = 17\nsensor_fov_deg = 360\n");
	ASSERT_EQ(simulated.exit_code, 0) << simulated.out;
	const std::string rawlog = dir.file("dense.rawlog");
	const std::string ekf = sourcePath("configs/ekf.ini");
	const auto [code, text] = esif::test::finish(esif::test::spawnEsif(
		{"run", "-q", "--no-figures", "--config", ekf, "--rawlog", rawlog, "--out", dir.file("o")},
		esif::test::SpawnLimits{{}, rlim_t{600} << 20, {}}));
	EXPECT_EQ(code, 1) << text;
	EXPECT_EQ(text, "esif: error: " + ekf + ": plugin EkfSlam would need 2.54 GiB for its estimate of the 9229 "
					"landmarks of " + rawlog + ", more than the 0.586 GiB this process may use (RLIMIT_AS): "
					"choose a sparse information filter for a map this size\n");
	EXPECT_FALSE(fs::exists(dir.file("o")));
}
