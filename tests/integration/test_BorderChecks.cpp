// Bad input stopped at the border, through the esif binary as a user runs
// it: for each kind, the exact error line and the exit code (1 bad input or
// config, 3 a run that failed). Implausible dataset fields, a broken plugin
// file among good ones, scenarios too large to simulate, a plugin out of
// memory, malformed ground truth, and Ceres/SuiteSparse staying quiet when
// the full-SLAM solve fails.

#include <EsifTestSupport.h>

#include <esif/formats/RawlogReader.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace
{
using esif::test::CommandResult;
using esif::test::runEsif;
using esif::test::TempDir;

const std::string kTestPlugins = ESIF_TEST_PLUGIN_DIR;

/// `r` printed exactly `lines` (each with its newline) and exited with `exit_code`.
void expectOutput(const CommandResult& r, int exit_code, const std::string& lines)
{
	EXPECT_EQ(r.exit_code, exit_code) << r.out;
	EXPECT_EQ(r.out, lines);
}

std::string runArgs(const std::string& config, const std::string& rawlog, const std::string& out)
{
	return "run -q --config '" + config + "' --rawlog '" + rawlog + "' --out '" + out + "'";
}

std::string write(const std::string& path, const std::string& text)
{
	std::ofstream(path) << text;
	return path;
}

// ---- esif import victoria-park: every field checked, file:line and field named

TEST(BorderChecks, ImportRejectsANegativeVarianceAndAHugeCoordinate)
{
	TempDir dir;
	const std::string first = "ODOMETRY 0 1 0.1 0 0 0.0001 0 0 4e-06 0 4e-06\n";
	const auto in = write(dir.file("vp.txt"), first + "ODOMETRY 1 2 0.1 0 0 -1 0 0 4e-06 0 4e-06\n");
	const auto args = "import victoria-park --in '" + in + "' --out '" + dir.file("vp.rawlog") + "'";
	expectOutput(
		runEsif(args), 1, "esif: error: " + in + ":2: ODOMETRY c11 = -1: a variance must be in (0, 1e+06]\n");
	write(in, first + "LANDMARK 1 7 1e300 2 0.4 0 0.4\n");
	expectOutput(
		runEsif(args), 1,
		"esif: error: " + in + ":2: LANDMARK x = 1e+300: must be within +-1000 m (farthest plausible landmark)\n");
	EXPECT_FALSE(std::filesystem::exists(dir.file("vp.rawlog")));
	expectOutput(
		runEsif(args + " --dt-s 1e9"), 1,
		"esif: error: import victoria-park: --dt-s = 1e+09: must be in (0, 3600] (one hour between poses)\n");
}

// ---- plugin folders: a broken file is a warning, not the end of every plugin

/// A plugin folder with the test plugins' library (a real one) and two
/// garbage files: one named like a plugin (libesif_plugin_*.so, what the
/// loader looks for) and one that is not (libesif_broken.so: never opened).
std::string folderWithABrokenPlugin(const TempDir& dir)
{
	const std::string folder = dir.file("plugins");
	std::filesystem::create_directories(folder);
	std::filesystem::copy_file(
		kTestPlugins + "/libesif_plugin_test_compare.so", folder + "/libesif_plugin_test_compare.so");
	write(folder + "/libesif_plugin_broken.so", "not a library\n");
	write(folder + "/libesif_broken.so", "not a library either\n");
	return folder;
}

/// The warning for the garbage file named like a plugin: esif checks the
/// ELF header of its sealed copy before the dynamic loader maps it.
std::string brokenWarning(const std::string& folder)
{
	return "esif: warning: " + folder + "/libesif_plugin_broken.so: cannot load plugin, skipped (not an ELF file)\n";
}

TEST(BorderChecks, PluginsListsTheGoodPluginsAndWarnsAboutTheBrokenFile)
{
	TempDir dir;
	const auto folder = folderWithABrokenPlugin(dir);
	const auto r = runEsif("plugins --plugin-dir '" + folder + "'");
	EXPECT_EQ(r.exit_code, 0) << r.out;
	EXPECT_EQ(r.out.rfind(brokenWarning(folder), 0), 0u) << r.out;	// first line, once
	EXPECT_EQ(r.out.find("cannot load", brokenWarning(folder).size()), std::string::npos) << r.out;
	EXPECT_EQ(r.out.find("libesif_broken.so"), std::string::npos) << r.out;	// not a plugin file name
	for (const char* plugin : {"test::FailingFilter    (", "test::OutOfMemoryFilter    (", "EkfSlam    ("})
		EXPECT_NE(r.out.find(plugin), std::string::npos) << plugin << " in " << r.out;
}

TEST(BorderChecks, ARunStillFindsItsPluginBesideABrokenFileAndAMissingOneNamesIt)
{
	TempDir dir;
	const auto folder = folderWithABrokenPlugin(dir);
	const auto rawlog = dir.file("small.rawlog");
	ASSERT_EQ(esif::test::simulateSmall(rawlog).exit_code, 0);
	// test::FailingFilter, loaded beside the broken file, fails at step 5 as configured.
	const auto failing =
		write(dir.file("failing.ini"), "[esif]\nplugin = test::FailingFilter\n[failing]\nfail_at_step = 5\n");
	expectOutput(
		runEsif(runArgs(failing, rawlog, dir.file("out")) + " --plugin-dir '" + folder + "'"), 3,
		brokenWarning(folder) + "esif: numerical failure: " + rawlog +
			": step 5: test::FailingFilter fails here on purpose (fail_at_step)\n");
	// A plugin found nowhere: an error naming the broken file, which may have been it.
	const auto missing = write(dir.file("missing.ini"), "[esif]\nplugin = test::NoSuchFilter\n");
	const auto r = runEsif(runArgs(missing, rawlog, dir.file("out2")) + " --plugin-dir '" + folder + "'");
	EXPECT_EQ(r.exit_code, 1) << r.out;
	std::istringstream lines(r.out);
	std::string warning, error, extra;
	std::getline(lines, warning);
	std::getline(lines, error);
	EXPECT_FALSE(std::getline(lines, extra)) << r.out;
	EXPECT_EQ(warning + "\n", brokenWarning(folder));
	EXPECT_EQ(error.rfind("esif: error: unknown plugin 'test::NoSuchFilter' (available: ", 0), 0u) << error;
	const std::string tail = "; files that failed to load, one may be it: " + folder +
		"/libesif_plugin_broken.so (not an ELF file)";
	ASSERT_GE(error.size(), tail.size());
	EXPECT_EQ(error.substr(error.size() - tail.size()), tail);
}

// ---- esif simulate: sizes checked before anything is allocated

TEST(BorderChecks, SimulateRejectsScenariosTooLargeBeforeAllocating)
{
	TempDir dir;
	const auto out = dir.file("big.rawlog");
	const auto simulate = [&](const std::string& ini) {
		return runEsif("simulate --config '" + ini + "' --out '" + out + "'");
	};
	// The case: 1e12 grid features, std::bad_alloc before this check.
	auto ini = write(dir.file("grid.ini"), "[simulation]\nfeatures_per_side = 1000000\n");
	expectOutput(
		simulate(ini), 1, "esif: error: " + ini + ": [simulation] features_per_side = 1000000: must be in [1, 1000]\n");
	// Within the per-key bound, but twins double the grid past the landmark cap.
	ini = write(
		dir.file("twins.ini"),
		"[simulation]\nfeatures_per_side = 1000\nworld_size_m = 1000\ncluster_pair_distance_m = 0.1\n");
	expectOutput(
		simulate(ini), 1,
		"esif: error: " + ini +
			": [simulation] features_per_side = 1000, cluster_pair_distance_m = 0.1: 2000000 landmarks (grid features "
			"and their twins), above the cap of 1000000\n");
	// A dense world seen with a long-range 360-degree sensor: 1 landmark per
	// m^2 x pi 50^2 m^2 = 7854 per scan, x 2000 steps = 1.57e7 measurements.
	ini = write(
		dir.file("dense.ini"),
		"[simulation]\nfeatures_per_side = 1000\nworld_size_m = 1000\nsensor_max_range_m = 50\nsensor_fov_deg = "
		"360\nsteps = 2000\nstart_x_m = 500\nstart_y_m = 500\n");
	expectOutput(
		simulate(ini), 1,
		"esif: error: " + ini +
			": [simulation] steps = 2000, features_per_side = 1000, sensor_max_range_m = 50: about 1.57e+07 "
			"measurements expected (7854 per scan x 2000 steps), above the cap of 10000000 (per scan: the landmarks "
			"within sensor_max_range_m and sensor_fov_deg at the grid's density, plus spurious_rate)\n");
	EXPECT_FALSE(std::filesystem::exists(out));
}

// ---- out of memory in a plugin: a failed run naming the step, exit code 3

/// Distinct landmark IDs measured in the first `steps` steps of `rawlog`.
std::size_t landmarksIn(const std::string& rawlog, std::size_t steps)
{
	const esif::Rawlog log = esif::readRawlog(rawlog);
	std::set<esif::LandmarkId> ids;
	for (std::size_t k = 0; k < std::min(steps, log.steps.size()); ++k)
		if (log.steps[k].scan)
			for (const auto& m : log.steps[k].scan->measurements)
				if (m.id) ids.insert(*m.id);
	return ids.size();
}

TEST(BorderChecks, OutOfMemoryInAPluginNamesTheStepThePluginAndItsLandmarks)
{
	TempDir dir;
	const auto rawlog = dir.file("small.rawlog");
	ASSERT_EQ(esif::test::simulateSmall(rawlog).exit_code, 0);
	const std::string plugin_dir = " --plugin-dir '" + kTestPlugins + "'";
	auto ini = write(
		dir.file("oom.ini"), "[esif]\nplugin = test::OutOfMemoryFilter\n[out_of_memory]\nfail_at_step = 40\n");
	const std::size_t before_step_40 = landmarksIn(rawlog, 40);
	ASSERT_GT(before_step_40, 0u);
	expectOutput(
		runEsif(runArgs(ini, rawlog, dir.file("out")) + plugin_dir), 3,
		"esif: numerical failure: " + rawlog +
			": out of memory at step 40 in plugin esif::test::OutOfMemoryFilter (state of " +
			std::to_string(before_step_40) + " landmarks)\n");
	// In finish(), where a batch optimiser does its work: after every step.
	ini = write(
		dir.file("oom_finish.ini"), "[esif]\nplugin = test::OutOfMemoryFilter\n[out_of_memory]\nfail_in = finish\n");
	expectOutput(
		runEsif(runArgs(ini, rawlog, dir.file("out_finish")) + plugin_dir), 3,
		"esif: numerical failure: " + rawlog +
			": out of memory after the last step in plugin esif::test::OutOfMemoryFilter (state of " +
			std::to_string(landmarksIn(rawlog, 1u << 20)) + " landmarks)\n");
}

// ---- ground truth: every malformed field named

TEST(BorderChecks, AFractionalGroundTruthIdIsNamedAsSuch)
{
	TempDir dir;
	const auto rawlog = dir.file("small.rawlog");
	ASSERT_EQ(esif::test::simulateSmall(rawlog).exit_code, 0);
	// Line 2 of the simulator's file gets a fractional ID: before, it was
	// rounded and reported as a duplicate.
	const auto truth = dir.file("small_ground_truth.txt");
	std::istringstream in(esif::test::readText(truth));
	std::ostringstream out;
	std::string line;
	for (int n = 1; std::getline(in, line); ++n)
	{
		if (n == 2) line = "1.5 2.5 0 5 0 0 0.5";
		out << line << "\n";
	}
	write(truth, out.str());
	const auto ini = write(dir.file("ekf.ini"), "[esif]\nplugin = EkfSlam\n");
	expectOutput(
		runEsif(runArgs(ini, rawlog, dir.file("out"))), 1,
		"esif: error: " + truth + ":2: column 7 (ID) = 0.5: a landmark ID must be an integer, not fractional\n");
}

// ---- Ceres: a failed solve is told in the plugin's own lines only

TEST(BorderChecks, AFailingCeresSolvePrintsNoGlogOrSuiteSparseText)
{
	// The robot drives exactly onto the landmark it saw 2 m ahead and sees it
	// again: the new pose's warm start (refine_new_poses) and the final
	// solve evaluate range-bearing terms at zero distance (NaN Jacobian), and
	// the covariances fail. Before, glog dumped the residual block (30 lines)
	// and CHOLMOD printed "CHOLMOD error: invalid xtype".
	TempDir dir;
	const auto in = write(
		dir.file("degenerate.txt"),
		"LANDMARK 0 100 2 0 0.4 0 0.4\n"
		"ODOMETRY 0 1 2 0 0 0.0001 0 0 0.0001 0 0.0001\n"
		"LANDMARK 1 100 0.5 0 0.4 0 0.4\n"
		"ODOMETRY 1 2 1 0 0 0.0001 0 0 0.0001 0 0.0001\n"
		"LANDMARK 2 100 1 0 0.4 0 0.4\n");
	const auto rawlog = dir.file("degenerate.rawlog");
	ASSERT_EQ(runEsif("import victoria-park --in '" + in + "' --out '" + rawlog + "'").exit_code, 0);
	const auto ini = write(dir.file("ceres.ini"), "[esif]\nplugin = CeresFullSlam\n");
	const auto r = runEsif(runArgs(ini, rawlog, dir.file("out")));
	EXPECT_EQ(r.exit_code, 0) << r.out;
	std::istringstream lines(r.out);
	std::size_t count = 0;
	for (std::string line; std::getline(lines, line); ++count)
		EXPECT_EQ(line.rfind("esif: warning: ceres_full: ", 0), 0u) << line;
	// The failed final solve, the implausible optimum, the covariances.
	EXPECT_EQ(count, 3u) << r.out;
	EXPECT_NE(r.out.find("the final solve failed"), std::string::npos) << r.out;
}

}  // namespace
