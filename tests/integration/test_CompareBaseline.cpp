// `esif compare` against the optimization baseline (the run whose stats
// formulation is full_slam, here the Ceres plugin): accuracy ratios with
// ground truth, the baseline as default reference without it, and the
// book's Table 5.1 layout with the estimators in their columns.

#include <EsifTestSupport.h>

#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

namespace
{
using esif::test::readText;
using esif::test::runEsif;
using esif::test::sourcePath;
using esif::test::TempDir;

/// The line of `text` starting with `head`, or "" when there is none.
std::string lineStarting(const std::string& text, const std::string& head, std::size_t from = 0)
{
	const auto at = text.find("\n" + head, from);
	if (at == std::string::npos) return "";
	return text.substr(at + 1, text.find('\n', at + 1) - at - 1);
}

/// The last cell of a table line (the last run's column).
std::string lastCell(const std::string& line)
{
	std::istringstream in(line);
	std::string cell;
	for (std::string c; in >> c;) cell = c;
	return cell;
}

/// The small rawlog with ground truth beside it, a copy without, and
/// configs for the EKF, D-SLAM and the Ceres full-SLAM baseline.
class CompareBaseline : public ::testing::Test
{
   protected:
	static void SetUpTestSuite()
	{
		dir_ = std::make_unique<TempDir>();
		const auto r = esif::test::simulateSmall(dir_->file("small.rawlog"));
		ASSERT_EQ(r.exit_code, 0) << r.out;
		std::filesystem::copy_file(dir_->file("small.rawlog"), dir_->file("nogt.rawlog"));
		std::ofstream(dir_->file("ekf.ini")) << "[esif]\nplugin = EkfSlam\nlabel = ekf\n";
		std::ofstream(dir_->file("dslam.ini")) << "[esif]\nplugin = Dslam\nlabel = dslam\n";
		std::ofstream(dir_->file("full.ini")) << "[esif]\nplugin = CeresFullSlam\nlabel = full\n";
		std::ofstream(dir_->file("full2.ini")) << "[esif]\nplugin = CeresFullSlam\nlabel = full2\n";
	}
	static void TearDownTestSuite() { dir_.reset(); }

	static esif::test::CommandResult compare(
		const std::string& configs, const std::string& rawlog, const std::string& out, const std::string& extra = "")
	{
		std::string list;
		std::stringstream ss(configs);
		for (std::string c; std::getline(ss, c, ',');) list += (list.empty() ? "" : ",") + dir_->file(c);
		return runEsif(
			"compare --configs '" + list + "' --rawlog '" + dir_->file(rawlog) + "' --out '" + dir_->file(out) +
			"' " + extra);
	}

	static std::unique_ptr<TempDir> dir_;
};
std::unique_ptr<TempDir> CompareBaseline::dir_;

TEST_F(CompareBaseline, RatiosToTheOptimumWithGroundTruth)
{
	const auto r = compare("ekf.ini,dslam.ini,full.ini", "small.rawlog", "gt");
	ASSERT_EQ(r.exit_code, 0) << r.out;
	const auto ratio = lineStarting(r.out, "base_landmark_rmse_ratio");
	ASSERT_FALSE(ratio.empty()) << r.out;
	EXPECT_EQ(lastCell(ratio), "1") << ratio;  // the baseline's own column, last
	EXPECT_FALSE(lineStarting(r.out, "base_ate_ratio").empty()) << r.out;
	EXPECT_NE(r.out.find("base_*: ratio to the optimization baseline 'full' (1 = as accurate as the optimum)\n"),
			  std::string::npos)
		<< r.out;
	EXPECT_EQ(r.out.find("ref_"), std::string::npos) << "ground truth known: no reference columns\n" << r.out;
	EXPECT_NE(readText(dir_->file("gt/comparison.csv")).find("base_landmark_rmse_ratio,base_ate_ratio"),
			  std::string::npos);
	EXPECT_NE(readText(dir_->file("gt/full/stats.json")).find("\"formulation\": \"full_slam\""), std::string::npos);

	// Table 5.1: full SLAM and D-SLAM in the book's columns, the EKF after them.
	const auto table = r.out.find("Table 5.1 layout: performance of exactly sparse information filters\n");
	ASSERT_NE(table, std::string::npos) << r.out;
	const auto poses = lineStarting(r.out, "Number of poses", table);
	EXPECT_NE(poses.find("200"), std::string::npos) << poses;  // every pose of full SLAM
	const auto md = readText(dir_->file("gt/comparison.md"));
	EXPECT_NE(md.find("| | full SLAM | D-SLAM | D-SLAM local map joining filter | SLSJF | ekf |"), std::string::npos)
		<< md;
	EXPECT_NE(md.find("| Number of poses | 200 | 0 | not available | not available | 1 |"), std::string::npos) << md;
	EXPECT_NE(md.find("base_*: ratio to the optimization baseline 'full'"), std::string::npos) << md;
}

TEST_F(CompareBaseline, WithoutGroundTruthTheBaselineIsTheReference)
{
	const auto r = compare("ekf.ini,dslam.ini,full.ini", "nogt.rawlog", "nogt");
	ASSERT_EQ(r.exit_code, 0) << r.out;
	EXPECT_NE(r.out.find("ref_*: difference from the optimization baseline 'full'"), std::string::npos) << r.out;
	const auto traj = lineStarting(r.out, "ref_traj_rms_m");
	ASSERT_FALSE(traj.empty()) << r.out;
	EXPECT_EQ(lastCell(traj), "0") << traj;
	EXPECT_EQ(r.out.find("base_"), std::string::npos) << "no ground truth: no ratios\n" << r.out;
	// ... and the whole-state test of an information-form filter is computed
	// against it (the baseline ran first).
	const auto dslam = esif::Stats::load(dir_->file("nogt/dslam/stats.json"));
	EXPECT_EQ(dslam.text("state_nees_reference").value_or(""), dir_->file("nogt/full"));
	EXPECT_GT(esif::test::statNumber(dslam, "state_nees_dof"), 0);

	// --reference still wins.
	const auto ekf_ref = compare("ekf.ini,full.ini", "nogt.rawlog", "nogt_ekf", "--reference ekf");
	ASSERT_EQ(ekf_ref.exit_code, 0) << ekf_ref.out;
	EXPECT_NE(ekf_ref.out.find("ref_*: difference from run 'ekf'"), std::string::npos) << ekf_ref.out;
}

TEST_F(CompareBaseline, SeveralBaselinesTheFirstWithAWarning)
{
	const auto r = compare("full2.ini,ekf.ini,full.ini", "small.rawlog", "two");
	ASSERT_EQ(r.exit_code, 0) << r.out;
	EXPECT_NE(r.out.find("esif: warning: several full-SLAM runs (full2, full): the optimization baseline is the "
						 "first, 'full2'\n"),
			  std::string::npos)
		<< r.out;
	EXPECT_NE(r.out.find("ratio to the optimization baseline 'full2'"), std::string::npos) << r.out;
	// The second full-SLAM run gets a column of its own after the book's.
	const auto md = readText(dir_->file("two/comparison.md"));
	EXPECT_NE(md.find("| SLSJF | ekf | full |"), std::string::npos) << md;
}

TEST_F(CompareBaseline, WithoutBaselineNeitherRatiosNorDefaultReference)
{
	const auto r = compare("ekf.ini,dslam.ini", "small.rawlog", "nobase");
	ASSERT_EQ(r.exit_code, 0) << r.out;
	EXPECT_EQ(r.out.find("base_"), std::string::npos) << r.out;
	EXPECT_EQ(r.out.find("ref_"), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("Table 5.1 layout"), std::string::npos) << r.out;
}

}  // namespace
