// `esif localmaps check` through the binary, as a user runs it: each local
// map and the joined state after each fusion held against the truth (the
// committed grid196 rawlog) or another run (the full-SLAM optimum), the
// whole-state NEES in stats.json, and the one-line errors.

#include <EsifTestSupport.h>

#include <esif/formats/StatsJson.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace
{
using esif::test::expectOneErrorLine;
using esif::test::quoted;
using esif::test::runEsif;
using esif::test::sourcePath;
using esif::test::TempDir;

const std::string kGrid196 = sourcePath("rawlogs/grid196.rawlog");

double insideFraction(const std::vector<std::map<std::string, std::string>>& rows)
{
	double inside = 0;
	for (const auto& r : rows) inside += r.at("inside") == "1";
	return inside / static_cast<double>(rows.size());
}

std::string checkCommand(const std::string& config, const std::string& rawlog, const std::string& out,
						 const std::string& extra = "")
{
	return "localmaps check -q --config " + quoted(sourcePath(config)) + " --rawlog " + quoted(rawlog) + " " + extra +
		   " --out " + quoted(out);
}

TEST(LocalMapsCheck, SlsjfOnGrid196HasConsistentLocalMapsAndAConsistentJoinedState)
{
	TempDir dir;
	const auto r = runEsif(checkCommand("configs/slsjf.ini", kGrid196, dir.file("check")));
	ASSERT_EQ(r.exit_code, 0) << r.out;
	const auto maps = esif::test::readCsvRows(dir.file("check/local_maps_nees.csv"));
	const auto fusions = esif::test::readCsvRows(dir.file("check/fusion_nees.csv"));
	EXPECT_TRUE(fs::exists(dir.file("check/consistency.png")));
	ASSERT_GT(maps.size(), 50u);  // 3000 steps in local maps of 45
	EXPECT_EQ(fusions.size(), maps.size());
	// On data with the filter's own noise model the local maps are
	// consistent: about 95% inside, binomial standard deviation
	// sqrt(0.95 * 0.05 / 67) = 2.7%, so 4 sigma below is 84%.
	EXPECT_GE(insideFraction(maps), 0.84);
	EXPECT_GE(insideFraction(fusions), 0.84);
	// The states grow: the last holds every landmark and every map's end pose.
	EXPECT_EQ(std::stoul(fusions.back().at("poses_compared")), maps.size());
	EXPECT_GT(std::stoul(fusions.back().at("landmarks_compared")), 150u);
	EXPECT_EQ(fusions.back().at("inside"), "1");  // the book's claim (Sec. 5.6.1), on this fixed draw
}

TEST(LocalMapsCheck, AgainstTheOptimumTheJoinedStateIsNoWorseThanAgainstTheTruth)
{
	TempDir dir;
	ASSERT_EQ(runEsif("run -q --config " + quoted(sourcePath("configs/ceres_full.ini")) + " --rawlog " +
					  quoted(kGrid196) + " --out " + quoted(dir.file("opt")))
				  .exit_code,
			  0);
	const auto r = runEsif(
		checkCommand("configs/dslam_lmj.ini", kGrid196, dir.file("check"), "--reference-run " + quoted(dir.file("opt"))));
	ASSERT_EQ(r.exit_code, 0) << r.out;
	const auto fusions = esif::test::readCsvRows(dir.file("check/fusion_nees.csv"));
	ASSERT_FALSE(fusions.empty());
	// The optimum shares the filter's error, so the NEES against it is at
	// most that against the truth in expectation: below the upper bound.
	const auto& last = fusions.back();
	EXPECT_LT(std::stod(last.at("nees")), std::stod(last.at("upper95")));
	EXPECT_EQ(last.at("poses_compared"), "0");	// D-SLAM map joining holds features only (eq. 4.1)
}

TEST(LocalMapsCheck, StatsJsonCarriesTheWholeStateTestAgainstTheTruthOrAReferenceRun)
{
	TempDir dir;
	ASSERT_EQ(runEsif("run -q --config " + quoted(sourcePath("configs/slsjf.ini")) + " --rawlog " + quoted(kGrid196) +
					  " --out " + quoted(dir.file("slsjf")))
				  .exit_code,
			  0);
	const auto s = esif::Stats::load(dir.file("slsjf/stats.json"));
	EXPECT_EQ(s.text("state_nees_reference").value_or(""), "truth");
	const double dof = esif::test::statNumber(s, "state_nees_dof");
	// Every landmark (2) and every local map's end pose (3).
	EXPECT_EQ(dof, 2 * esif::test::statNumber(s, "landmarks") + 3 * esif::test::statNumber(s, "state_nees_poses"));
	EXPECT_LT(esif::test::statNumber(s, "state_nees_lower95"), esif::test::statNumber(s, "state_nees_upper95"));

	// The optimum against itself (its trajectory.tum is its final estimate
	// of every pose, unlike a filter's, which is its estimate at the time):
	// zero error but for the files' 17 digits, NEES 0, below the interval.
	const auto optimum = [&](const std::string& out, const std::string& extra) {
		return runEsif("run -q --config " + quoted(sourcePath("configs/ceres_full.ini")) + " --rawlog " +
					   quoted(kGrid196) + " " + extra + " --out " + quoted(dir.file(out)));
	};
	ASSERT_EQ(optimum("opt", "").exit_code, 0);
	ASSERT_EQ(optimum("again", "--reference-run " + quoted(dir.file("opt"))).exit_code, 0);
	const auto again = esif::Stats::load(dir.file("again/stats.json"));
	EXPECT_EQ(again.text("state_nees_reference").value_or(""), dir.file("opt"));
	EXPECT_NEAR(esif::test::statNumber(again, "state_nees"), 0, 1e-6);
	EXPECT_EQ(esif::test::statNumber(again, "state_nees_consistent"), 0);
	EXPECT_EQ(esif::test::statNumber(again, "state_nees_poses"), 3000);  // every step's pose

	// The EKF holds a covariance, not an information matrix: null.
	ASSERT_EQ(runEsif("run -q --config " + quoted(sourcePath("configs/ekf.ini")) + " --rawlog " + quoted(kGrid196) +
					  " --out " + quoted(dir.file("ekf")))
				  .exit_code,
			  0);
	EXPECT_FALSE(esif::Stats::load(dir.file("ekf/stats.json")).number("state_nees"));
}

TEST(LocalMapsCheck, AReferenceRunOfAnotherRawlogIsOneLineNamingItsTrajectory)
{
	TempDir dir;
	fs::create_directories(dir.file("short"));
	std::ofstream(dir.file("short/trajectory.tum")) << "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n";
	std::ofstream(dir.file("short/landmarks.txt")) << "1 0 0 1 0 1\n";
	const auto r = runEsif(
		checkCommand("configs/slsjf.ini", kGrid196, dir.file("check"), "--reference-run " + quoted(dir.file("short"))));
	expectOneErrorLine(r, "trajectory.tum: 2 rows, the rawlog has 3000 steps");
	EXPECT_FALSE(fs::exists(dir.file("check")));
}

TEST(LocalMapsCheck, ARawlogWithoutTruthNeedsAReferenceRun)
{
	TempDir dir;
	fs::copy_file(kGrid196, dir.file("alone.rawlog"));
	const auto r = runEsif(checkCommand("configs/slsjf.ini", dir.file("alone.rawlog"), dir.file("check")));
	expectOneErrorLine(r, "--reference-run");
	EXPECT_FALSE(fs::exists(dir.file("check")));
}

TEST(LocalMapsCheck, APluginThatJoinsNoLocalMapsIsOneLine)
{
	TempDir dir;
	const auto r = runEsif(checkCommand("configs/ekf.ini", kGrid196, dir.file("check")));
	expectOneErrorLine(r, "is not a local-map joining plugin");
	EXPECT_FALSE(fs::exists(dir.file("check")));
}

}  // namespace
