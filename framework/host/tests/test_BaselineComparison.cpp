// The optimization baseline of esif compare: found by stats "formulation",
// the first of several with a warning, and each run's accuracy as a ratio of
// the baseline's.

#include <esif/compare/BaselineComparison.h>
#include <esif/compare/ComparisonTable.h>

#include <gtest/gtest.h>

namespace
{
esif::Stats run(const std::string& label, const std::string& formulation, std::optional<double> landmark_rmse,
				std::optional<double> ate)
{
	esif::Stats s;
	s.set("label", esif::StatValue(label));
	if (!formulation.empty()) s.set("formulation", esif::StatValue(formulation));
	s.set("landmark_rmse_m", landmark_rmse);
	s.set("ate_rmse_m", ate);
	return s;
}

TEST(BaselineComparison, FormulationOfOldStatsIsOther)
{
	EXPECT_EQ(esif::runFormulation(run("old", "", 1.0, 1.0)), "other");
	EXPECT_EQ(esif::runFormulation(run("new", "dslam", 1.0, 1.0)), "dslam");
}

TEST(BaselineComparison, FindsTheFirstFullSlamRun)
{
	EXPECT_FALSE(esif::findBaseline({run("ekf", "ekf_slam", 1.0, 1.0), run("old", "", 1.0, 1.0)}).index);

	const auto one = esif::findBaseline({run("ekf", "ekf_slam", 1.0, 1.0), run("ceres", "full_slam", 1.0, 1.0)});
	EXPECT_EQ(one.index.value_or(99), 1u);
	EXPECT_FALSE(one.warning);

	const auto two = esif::findBaseline(
		{run("ekf", "ekf_slam", 1.0, 1.0), run("c1", "full_slam", 1.0, 1.0), run("c2", "full_slam", 1.0, 1.0)});
	EXPECT_EQ(two.index.value_or(99), 1u);
	ASSERT_TRUE(two.warning);
	EXPECT_EQ(*two.warning, "several full-SLAM runs (c1, c2): the optimization baseline is the first, 'c1'");
}

TEST(BaselineComparison, GroundTruthFiguresOfAnyRun)
{
	EXPECT_FALSE(esif::hasGroundTruthFigures({run("a", "", std::nullopt, std::nullopt)}));
	EXPECT_TRUE(esif::hasGroundTruthFigures({run("a", "", std::nullopt, std::nullopt), run("b", "", 0.2, 0.3)}));
}

TEST(BaselineComparison, RatiosToTheBaseline)
{
	std::vector<esif::Stats> runs = {
		run("ekf", "ekf_slam", 0.3, 0.5),
		run("ceres", "full_slam", 0.1, 0.25),
		run("broken", "dslam", std::nullopt, 0.5),
	};
	esif::setBaselineRatios(runs, 1);
	EXPECT_DOUBLE_EQ(runs[0].number("base_landmark_rmse_ratio").value_or(-1), 3.0);
	EXPECT_DOUBLE_EQ(runs[0].number("base_ate_ratio").value_or(-1), 2.0);
	EXPECT_EQ(runs[1].number("base_landmark_rmse_ratio").value_or(-1), 1.0);
	EXPECT_EQ(runs[1].number("base_ate_ratio").value_or(-1), 1.0);
	// A missing figure gives null, which the tables show as "-".
	ASSERT_TRUE(runs[2].get("base_landmark_rmse_ratio"));
	EXPECT_TRUE(std::holds_alternative<std::nullptr_t>(*runs[2].get("base_landmark_rmse_ratio")));
	EXPECT_DOUBLE_EQ(runs[2].number("base_ate_ratio").value_or(-1), 2.0);

	// The tables add the keys after the usual ones.
	const std::string text = esif::comparisonText(runs);
	EXPECT_NE(text.find("base_landmark_rmse_ratio"), std::string::npos) << text;
	EXPECT_NE(esif::comparisonMarkdown(runs).find("| base_ate_ratio | 2 | 1 | 2 |"), std::string::npos)
		<< esif::comparisonMarkdown(runs);
	EXPECT_NE(esif::comparisonCsv(runs).find("base_landmark_rmse_ratio,base_ate_ratio"), std::string::npos);
	EXPECT_EQ(esif::comparisonText({run("x", "", 1.0, 1.0)}).find("base_"), std::string::npos);
}

TEST(BaselineComparison, ZeroBaselineFigureGivesNull)
{
	std::vector<esif::Stats> runs = {run("ekf", "ekf_slam", 0.3, 0.5), run("ceres", "full_slam", 0.0, 0.25)};
	esif::setBaselineRatios(runs, 1);
	EXPECT_FALSE(runs[0].number("base_landmark_rmse_ratio"));
	EXPECT_FALSE(runs[1].number("base_landmark_rmse_ratio"));
	EXPECT_DOUBLE_EQ(runs[0].number("base_ate_ratio").value_or(-1), 2.0);
}

TEST(BaselineComparison, Note)
{
	EXPECT_EQ(esif::baselineNote("ceres"),
			  "base_*: ratio to the optimization baseline 'ceres' (1 = as accurate as the optimum)\n");
}

/// stats.json as the Ceres plugin writes it after its plausibility check
/// (hand-written here: the keys are plugin_* counters of its CostFigures).
esif::Stats baselineStats(const std::string& plugin_keys)
{
	return esif::Stats::fromJson(
		"{\n  \"label\": \"ceres\",\n  \"formulation\": \"full_slam\",\n  \"landmark_rmse_m\": 0.1" +
			plugin_keys + "\n}\n",
		"stats.json");
}

TEST(BaselineComparison, ImplausibleBaselineRemark)
{
	const auto implausible = baselineStats(
		",\n  \"plugin_optimum_plausible\": 0,\n  \"plugin_chi2_per_dof\": 7.1,\n  \"plugin_degenerate_poses\": 2");
	EXPECT_EQ(esif::baselineImplausibility(implausible).value_or("none"),
			  "baseline 'ceres' implausible: chi2/dof 7.1, 2 degenerate poses; ratios and differences against it "
			  "are not trustworthy");
	// Whatever figures the plugin gives.
	EXPECT_EQ(esif::baselineImplausibility(baselineStats(",\n  \"plugin_optimum_plausible\": 0")).value_or("none"),
			  "baseline 'ceres' implausible; ratios and differences against it are not trustworthy");
	// Plausible, or no check at all (an older plugin): no remark.
	EXPECT_FALSE(esif::baselineImplausibility(baselineStats(
		",\n  \"plugin_optimum_plausible\": 1,\n  \"plugin_chi2_per_dof\": 1.02,\n  \"plugin_degenerate_poses\": 0")));
	EXPECT_FALSE(esif::baselineImplausibility(baselineStats("")));
}

TEST(ComparisonTable, FailedRowsStatusExitCodeAndNote)
{
	std::vector<esif::Stats> runs = {run("ekf", "ekf_slam", 0.1, 0.2), esif::failedRunStats("bad", "X", 3, "esif: numerical failure: step 5"),
									 esif::notRunStats("dep", "Y", "its associations_from run 'bad' failed"),
									 esif::failedRunStats("worse", "Z", 1, "esif: error: f.ini: no")};
	EXPECT_FALSE(esif::isFailedRun(runs[0]));
	EXPECT_TRUE(esif::isFailedRun(runs[1]));
	EXPECT_TRUE(esif::isFailedRun(runs[2]));
	esif::markSucceededRuns(runs);
	EXPECT_EQ(runs[0].text("status").value_or(""), "ok");
	// The first failure in row order decides; a not-run row never does.
	EXPECT_EQ(esif::comparisonExitCode(runs), 3);
	EXPECT_EQ(esif::comparisonExitCode({runs[0], runs[2], runs[3], runs[1]}), 1);
	EXPECT_EQ(esif::comparisonExitCode({runs[0]}), 0);
	EXPECT_EQ(esif::failureNote(runs),
			  "run 'bad' failed (exit 3): esif: numerical failure: step 5\n"
			  "run 'dep' not run: its associations_from run 'bad' failed\n"
			  "run 'worse' failed (exit 1): esif: error: f.ini: no\n");
	const std::string md = esif::comparisonMarkdown(runs);
	EXPECT_NE(md.find("| plugin | - | X | Y | Z |\n| status | ok | failed | not run | failed |\n"
					  "| exit_code | - | 3 | - | 1 |\n"),
			  std::string::npos)
		<< md;

	// Without failures nothing changes: no status column.
	std::vector<esif::Stats> fine = {run("ekf", "ekf_slam", 0.1, 0.2)};
	esif::markSucceededRuns(fine);
	EXPECT_FALSE(fine[0].get("status"));
	EXPECT_EQ(esif::comparisonMarkdown(fine).find("status"), std::string::npos);
}

}  // namespace
