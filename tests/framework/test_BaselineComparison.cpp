// The optimization baseline of esif compare: found by stats "formulation",
// the first of several with a warning, and each run's accuracy as a ratio of
// the baseline's.

#include <esif/eval/BaselineComparison.h>
#include <esif/eval/ComparisonTable.h>

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

}  // namespace
