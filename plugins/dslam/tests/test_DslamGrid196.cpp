// The D-SLAM plugin end to end on the committed grid196 demo, side by side
// with the EKF plugin (book Sec. 3.5: "the difference between the feature
// location estimates from the two algorithms is not distinguishable"; D-SLAM
// is consistent and conservative, Fig. 3.8-3.10), and the exact sparseness of
// its information matrix (Sec. 3.2).

#include <EsifTestSupport.h>

#include <esif/eval/Evaluator.h>
#include <esif/formats/GroundTruth.h>

#include <gtest/gtest.h>

#include <set>
#include <utility>

namespace
{
using namespace esif;
using test::pluginCounter;

const std::string kGrid196 = test::sourcePath("rawlogs/grid196.rawlog");

struct Scored
{
	FilterPlugin::Ptr plugin;
	ReplayResult result;
	Accuracy accuracy;
};

Scored run(const std::string& plugin_class, const std::string& section, bool hide_ids)
{
	RawlogReadOptions opts;
	opts.hide_landmark_ids = hide_ids;
	const Rawlog log = readRawlog(kGrid196, opts);
	Scored s{test::makePlugin(plugin_class, section), {}, {}};
	s.result = replay(*s.plugin, log, {0, false});
	s.accuracy = test::scoreAgainstTruth(s.result, groundTruthPrefixFor(kGrid196));
	return s;
}

TEST(DslamGrid196, KnownIdsNearTheOptimumAndConservativeFromBothSides)
{
	const auto ekf = run("EkfSlam", "association = known_ids\n", false);
	const auto dslam = run("Dslam", "association = known_ids\n", false);
	const auto optimum = run("CeresFullSlam", "", false);
	const auto& a = dslam.accuracy;
	ASSERT_TRUE(a.landmark_rmse_m && optimum.accuracy.landmark_rmse_m && a.pose_consistent_fraction &&
				a.landmark_nees_mean && a.pose_nees_mean);
	std::cout << "grid196 known IDs: landmark RMSE D-SLAM " << *a.landmark_rmse_m << " m vs optimum "
			  << *optimum.accuracy.landmark_rmse_m << " m (EKF " << *ekf.accuracy.landmark_rmse_m << " m); ATE "
			  << *a.ate_rmse_m << " vs " << *optimum.accuracy.ate_rmse_m << " m; landmarks consistent "
			  << *a.landmark_consistent_fraction << ", landmark NEES mean " << *a.landmark_nees_mean
			  << ", poses consistent " << *a.pose_consistent_fraction << ", pose NEES mean " << *a.pose_nees_mean
			  << "\n";
	EXPECT_EQ(dslam.result.record.final_estimate.landmarks.size(), ekf.result.record.final_estimate.landmarks.size());
	// Accuracy against the full-SLAM optimum on the same rawlog: D-SLAM
	// drops the robot-map information of z_rob (Sec. 3.4) and relinearises
	// only the map updates, so it is worse than the optimum; measured 1.91x
	// (8.2 cm vs 4.3 cm; the EKF 10.1 cm, 2.3x). 2.5x leaves 30 % for
	// changes of tuning; the former bound, 1.5x the EKF (0.151 m), allowed
	// 3.5x the optimum.
	EXPECT_LE(*a.landmark_rmse_m, 2.5 * *optimum.accuracy.landmark_rmse_m);
	EXPECT_GE(*a.landmark_consistent_fraction, 0.95);
	// Consistency, both sides. One run cannot hold a mean NEES to a chi-square
	// band (its landmarks, and its steps, share one error draw; the
	// campaign tests in test_DslamCampaign.cpp do that), but it can bound a
	// conservative filter: D-SLAM's CI localisation makes its pose NEES
	// (measured 1.46, 0.49 of the 3 dof) lower than the expectation, and a
	// mean above 3 would be over-confidence. From below: a covariance five
	// times the error's (NEES under 0.2 of the dof) is no longer conservative
	// but uninformative, the failure a two-sided check exists for.
	EXPECT_GE(*a.pose_consistent_fraction, 0.90);
	EXPECT_LT(*a.pose_nees_mean, 3.0);
	EXPECT_GT(*a.pose_nees_mean, 0.2 * 3);
	EXPECT_GT(*a.landmark_nees_mean, 0.2 * 2);
	// Both localisation processes ran: CI fused at (almost) every admissible scan.
	EXPECT_GT(pluginCounter(*dslam.plugin, "ci_fusions"), 0.9 * pluginCounter(*dslam.plugin, "admissible_scans"));
	EXPECT_EQ(pluginCounter(*dslam.plugin, "ci_failures"), 0);
}

TEST(DslamGrid196, WithoutIdsMakesNoWrongAssociation)
{
	const auto s = run("Dslam", "association = jcbb\n", true);
	const auto& audit = s.result.audit;
	std::cout << "grid196 D-SLAM JCBB + relative test: " << audit.newCount() << " new, " << audit.matchedCount()
			  << " matched, " << audit.rejectedCount() << " rejected, " << audit.wrongCount() << " wrong\n";
	EXPECT_EQ(audit.wrongCount(), 0u);
	EXPECT_EQ(s.result.record.final_estimate.landmarks.size(), audit.filterToTrue().size());
	// Measured 315 of 13,717 (2.3 %): 160 first sightings held until a second
	// one confirms them, and about 150 sightings just outside tracking's gate
	// of a held feature but inside its new-feature gate, left ambiguous
	// (matching them made configs/sim/long_gap.ini diverge). 3 % leaves room
	// for tuning; a stall (every sighting ambiguous) is far beyond it.
	EXPECT_LT(audit.rejectedCount(), 3 * (audit.matchedCount() + audit.newCount()) / 100);
	EXPECT_LT(*s.accuracy.landmark_rmse_m, 0.2);
}

TEST(DslamGrid196, InformationMatrixIsExactlySparse)
{
	// With every map update from one scan (inadmissible scans skipped, the
	// map anchored by the first scan alone), Sec. 3.2's claim is exact: an
	// off-diagonal block of I is non-zero only if its two features were
	// observed in the same scan.
	const auto s = run("Dslam", "association = known_ids\nadmissible = skip\nanchor_scans = 1\n", false);
	const auto pattern = s.plugin->informationPattern();
	ASSERT_TRUE(pattern);
	const auto& landmarks = s.result.record.final_estimate.landmarks;  // variable order
	ASSERT_EQ(pattern->information.rows(), static_cast<Eigen::Index>(2 * landmarks.size()));

	std::set<std::pair<LandmarkId, LandmarkId>> co_observed;
	for (const auto& step : readRawlog(kGrid196).steps)
		if (step.scan)
			for (const auto& a : step.scan->measurements)
				for (const auto& b : step.scan->measurements) co_observed.insert({*a.id, *b.id});

	std::set<std::pair<LandmarkId, LandmarkId>> linked;
	for (int col = 0; col < pattern->information.outerSize(); ++col)
		for (Eigen::SparseMatrix<double>::InnerIterator it(pattern->information, col); it; ++it)
		{
			const LandmarkId i = landmarks[it.row() / 2].id, j = landmarks[col / 2].id;
			if (i == j || it.value() == 0.0) continue;
			linked.insert({i, j});
			EXPECT_TRUE(co_observed.count({i, j})) << "features " << i << " and " << j << " linked, never seen together";
		}
	// Conversely the links are the scans' (the skipped scans' pairs aside),
	// and a map of 164 features is far from dense.
	std::size_t pairs = 0;
	for (const auto& [i, j] : co_observed) pairs += i != j;
	std::cout << linked.size() << " linked feature pairs of " << pairs << " co-observed\n";
	EXPECT_GE(linked.size(), pairs * 9 / 10);
	EXPECT_LT(linked.size(), landmarks.size() * landmarks.size() / 5);
}

}  // namespace
