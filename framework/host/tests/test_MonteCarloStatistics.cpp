// The statistics of a Monte Carlo campaign (MonteCarloStatistics.h): the
// chi-square bounds against an independent implementation, the ANEES of an
// exactly consistent filter (a linear Kalman filter on a linear-Gaussian
// toy problem) inside them and of a mis-scaled one outside on either side,
// and the aggregation of a fixed set of run folders checked by hand.

#include <EsifTestSupport.h>

#include <esif/association/Chi2.h>
#include <esif/core/Errors.h>
#include <esif/eval/EstimationErrorFiles.h>
#include <esif/eval/MonteCarloStatistics.h>
#include <esif/montecarlo/MonteCarloCampaign.h>
#include <esif/montecarlo/MonteCarloCollect.h>
#include <esif/montecarlo/MonteCarloTables.h>
#include <esif/safeio/AtomicFile.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <filesystem>
#include <random>

namespace
{
using esif::AneesBounds;
using esif::CampaignRunErrors;
using esif::ConfigStatistics;

TEST(AneesBounds, MatchTheProjectsOwnChiSquareQuantile)
{
	// Chi2.h sums the incomplete-gamma series, Boost.Math inverts its own
	// implementation: two independent routes, agreeing to the bisection
	// tolerance of chi2Quantile (1e-12 relative) at dof where both work.
	for (const int dof : {2, 3})
		for (const std::size_t n : {1u, 8u, 50u, 200u})
		{
			const AneesBounds b = esif::aneesBounds(dof, n);
			const int total = dof * static_cast<int>(n);
			EXPECT_NEAR(b.lo, esif::chi2Quantile(0.025, total) / n, 1e-9 * b.hi) << dof << " " << n;
			EXPECT_NEAR(b.hi, esif::chi2Quantile(0.975, total) / n, 1e-9 * b.hi) << dof << " " << n;
		}
	// Bar-Shalom et al. (2001), Sec. 5.4.2 example: 50 runs of a 2-dof NEES,
	// bounds [1.5, 2.6] to the two digits the book prints.
	const AneesBounds b = esif::aneesBounds(2, 50);
	EXPECT_NEAR(b.lo, 1.5, 0.05);
	EXPECT_NEAR(b.hi, 2.6, 0.05);
	// Large campaigns: Boost stays exact where the series of Chi2.h would
	// overflow; the bounds close in on the dof as 1/sqrt(N).
	const AneesBounds wide = esif::aneesBounds(3, 5000);
	EXPECT_NEAR(wide.lo, 3 - 1.96 * std::sqrt(6.0 / 5000), 0.002);
	EXPECT_NEAR(wide.hi, 3 + 1.96 * std::sqrt(6.0 / 5000), 0.002);
}

/// A linear-Gaussian toy problem where the Kalman filter is exactly
/// consistent: a 3-state random walk x_k = F x_{k-1} + w (F a rotation-like
/// mixing), observed directly z = x + v, and a static 2-D point observed
/// with noise (the "landmark"). The filter's covariance is scaled by
/// `cov_scale` in the reported NEES: 1 is the true covariance, 0.5 an
/// overconfident filter, 2 a pessimistic one.
CampaignRunErrors simulateKalmanRun(std::mt19937& rng, double cov_scale, std::size_t index)
{
	std::normal_distribution<double> g(0.0, 1.0);
	const auto draw3 = [&] { return Eigen::Vector3d(g(rng), g(rng), g(rng)); };
	Eigen::Matrix3d F;
	F << 1.0, 0.1, 0.0, 0.0, 1.0, 0.1, 0.0, 0.0, 0.9;
	const Eigen::Matrix3d Q = 0.04 * Eigen::Matrix3d::Identity(), R = 0.25 * Eigen::Matrix3d::Identity();
	const Eigen::Matrix3d LQ = Q.llt().matrixL(), LR = R.llt().matrixL();
	Eigen::Vector3d x = Eigen::Vector3d::Zero(), xh = Eigen::Vector3d::Zero();
	Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
	CampaignRunErrors run;
	run.seed_index = index;
	run.wall_s = 1.0;
	for (std::size_t k = 1; k <= 150; ++k)
	{
		x = F * x + LQ * draw3();
		const Eigen::Vector3d z = x + LR * draw3();
		xh = F * xh;
		P = F * P * F.transpose() + Q;
		const Eigen::Matrix3d S = P + R;
		const Eigen::Matrix3d K = P * S.inverse();	// 3x3: fine
		xh += K * (z - xh);
		P = (Eigen::Matrix3d::Identity() - K) * P;
		P = 0.5 * (P + P.transpose());
		esif::PoseError row;
		row.step = k;
		row.error = xh - x;
		row.nees = esif::nees(row.error, cov_scale * P);
		run.poses.push_back(row);
	}
	// Landmarks: each a fixed point, prior N(0, I), observed 5 times with
	// noise 0.1 I; posterior covariance (I + 5 * 10 I)^-1 = I / 51.
	for (esif::LandmarkId id = 0; id < 20; ++id)
	{
		const Eigen::Vector2d truth(g(rng), g(rng));
		Eigen::Vector2d sum = Eigen::Vector2d::Zero();
		for (int m = 0; m < 5; ++m) sum += truth + std::sqrt(0.1) * Eigen::Vector2d(g(rng), g(rng));
		const Eigen::Vector2d estimate = sum * 10.0 / 51.0;	 // (prior mean 0) posterior mean
		esif::LandmarkError row;
		row.true_id = id;
		row.error = estimate - truth;
		row.nees = esif::nees(row.error, cov_scale * Eigen::Matrix2d::Identity() / 51.0);
		run.landmarks.push_back(row);
	}
	return run;
}

ConfigStatistics kalmanCampaign(double cov_scale, std::size_t runs = 50)
{
	std::mt19937 rng(20261129);
	std::vector<CampaignRunErrors> all;
	for (std::size_t r = 0; r < runs; ++r) all.push_back(simulateKalmanRun(rng, cov_scale, r));
	return esif::aggregateRuns("kf", all);
}

TEST(MonteCarloStatistics, AConsistentKalmanFilterIsInsideItsBounds)
{
	const ConfigStatistics c = kalmanCampaign(1.0);
	ASSERT_EQ(c.runs, 50u);
	ASSERT_EQ(c.steps.size(), 150u);
	// Each step's ANEES lies inside its 95% bounds with probability 0.95;
	// the steps of one campaign are correlated through the filter's memory,
	// so the share varies more than a binomial of 150: 0.85 is about four
	// binomial standard deviations (0.018) below 0.95, and still far above
	// the mis-scaled filters' shares below (about 0).
	ASSERT_TRUE(c.pose_steps_inside_fraction);
	EXPECT_GT(*c.pose_steps_inside_fraction, 0.85);
	// Mean over steps of ANEES (each with mean 3 and sd sqrt(6/50) = 0.35):
	// within 0.25 of 3 (the per-step sd over the ~150/10 effectively
	// independent steps is 0.09; 0.25 is almost 3 of those).
	EXPECT_NEAR(*c.pose_anees_mean, 3.0, 0.25);
	// Landmarks: 50 runs x 20 independent landmarks; their mean NEES has sd
	// sqrt(4 / 1000) = 0.063: within 0.2 of 2 (3 sd). Per landmark, 95% of
	// the ANEES inside: at least 80% of the 20 (binomial sd 0.05).
	EXPECT_NEAR(*c.landmark_anees, 2.0, 0.2);
	EXPECT_GE(*c.landmarks_inside_fraction, 0.8);
	EXPECT_TRUE(c.landmark_bounds.contains(*c.landmark_anees));
}

TEST(MonteCarloStatistics, AMisScaledFilterIsOutsideOnEitherSide)
{
	// Reporting half the covariance doubles every NEES (ANEES about 6, above
	// the upper bound 3.72 of 50 runs); twice the covariance halves it (1.5,
	// below the lower bound 2.36). A one-sided test would miss the second.
	const ConfigStatistics over = kalmanCampaign(0.5), under = kalmanCampaign(2.0);
	EXPECT_NEAR(*over.pose_anees_mean, 6.0, 0.5);
	EXPECT_NEAR(*under.pose_anees_mean, 1.5, 0.125);
	EXPECT_LT(*over.pose_steps_inside_fraction, 0.1);
	EXPECT_LT(*under.pose_steps_inside_fraction, 0.1);
	EXPECT_GT(*over.landmark_anees, over.landmark_bounds.hi);
	EXPECT_LT(*under.landmark_anees, under.landmark_bounds.lo);
}

TEST(EstimationErrors, TheInitialPoseHasNoNeesEvenWithACovarianceFloor)
{
	// The simulator's first step is a zero move with covariance 1e-10 I: a
	// NEES of 0 there would be an ANEES of 0, outside any bound, at every
	// campaign's step 0.
	esif::GroundTruth truth;
	truth.path = {esif::Pose2(0, 0, 0), esif::Pose2(1, 0, 0)};
	const std::vector<esif::TrajectoryPoint> trajectory = {
		{0, 0, {{0, 0, 0}, 1e-10 * Eigen::Matrix3d::Identity()}},
		{1, 0.1, {{1, 0.1, 0}, 0.01 * Eigen::Matrix3d::Identity()}}};
	const auto rows = esif::poseErrors(truth, trajectory);
	ASSERT_EQ(rows.size(), 2u);
	EXPECT_FALSE(rows[0].nees);
	ASSERT_TRUE(rows[1].nees);
	EXPECT_NEAR(*rows[1].nees, 1.0, 1e-12);	 // 0.1^2 / 0.01
}

TEST(EstimationErrors, ThePoseNeesIsSplitByTheMarginalsOfPositionAndHeading)
{
	// x and heading correlated (0.5), y independent, all variances 1; the
	// error (1, 0, 1). Whole pose: (1, 1) [[1, .5], [.5, 1]]^-1 (1, 1)^T
	// = (1 - .5 - .5 + 1) / 0.75 = 4/3. Position alone (marginal I): 1;
	// heading alone: 1. The split is of the marginals, not the conditionals,
	// so it does not add up to the whole.
	esif::GroundTruth truth;
	truth.path = {esif::Pose2(0, 0, 0), esif::Pose2(0, 0, 0)};
	Eigen::Matrix3d P = Eigen::Matrix3d::Identity();
	P(0, 2) = P(2, 0) = 0.5;
	const std::vector<esif::TrajectoryPoint> trajectory = {{0, 0, {{0, 0, 0}, Eigen::Matrix3d::Zero()}},
														   {1, 0.1, {{1, 0, 1}, P}}};
	const auto rows = esif::poseErrors(truth, trajectory);
	ASSERT_EQ(rows.size(), 2u);
	EXPECT_FALSE(rows[0].position_nees);
	EXPECT_FALSE(rows[0].heading_nees);
	EXPECT_NEAR(*rows[1].nees, 4.0 / 3.0, 1e-12);
	EXPECT_NEAR(*rows[1].position_nees, 1.0, 1e-12);
	EXPECT_NEAR(*rows[1].heading_nees, 1.0, 1e-12);

	// The file carries the split and reads it back exactly; a file of the
	// earlier layout (no split) still reads, with the split absent.
	esif::test::TempDir tmp;
	const std::string path = tmp.file("pose_errors.csv");
	esif::writeTextAtomically(path, esif::poseErrorsCsv(rows));
	const auto back = esif::readPoseErrors(path);
	ASSERT_EQ(back.size(), 2u);
	EXPECT_EQ(back[1].position_nees, rows[1].position_nees);
	EXPECT_EQ(back[1].heading_nees, rows[1].heading_nees);
	esif::writeTextAtomically(path, "step,ex_m,ey_m,eth_rad,nees\n1,0,0,0,2.5\n");
	const auto older = esif::readPoseErrors(path);
	ASSERT_EQ(older.size(), 1u);
	EXPECT_EQ(older[0].nees, 2.5);
	EXPECT_FALSE(older[0].position_nees);
	EXPECT_FALSE(older[0].heading_nees);
}

/// A finished run folder with the given rows, wall time and wrong associations.
void writeRunFolder(
	const std::string& dir, const std::vector<esif::PoseError>& poses, const std::vector<esif::LandmarkError>& lms,
	double wall_s, int da_wrong)
{
	esif::ensureDirectory(dir);
	esif::writeEstimationErrorFiles(dir, poses, lms);
	esif::writeTextAtomically(
		dir + "/stats.json",
		"{\n  \"wall_s\": " + std::to_string(wall_s) + ",\n  \"da_wrong\": " + std::to_string(da_wrong) + "\n}\n");
}

esif::PoseError pose(std::size_t step, double ex, double ey, double eth, std::optional<double> nees,
					 std::optional<double> position_nees = std::nullopt,
					 std::optional<double> heading_nees = std::nullopt)
{
	return {step, Eigen::Vector3d(ex, ey, eth), nees, position_nees, heading_nees};
}

esif::LandmarkError landmark(esif::LandmarkId id, double ex, double ey, double nees)
{
	return {id, Eigen::Vector2d(ex, ey), nees};
}

/// An empty campaign folder in `tmp`: one config (ekf.ini), seeds 1..runs.
std::string campaignFolder(const esif::test::TempDir& tmp, int runs)
{
	const std::string dir = tmp.file("mc");
	esif::ensureDirectory(dir);
	esif::writeTextAtomically(esif::campaign_layout::manifest(dir),
							  esif::CampaignPlan::create("scenario.ini", {"ekf.ini"}, 1, runs).iniText());
	return dir;
}

TEST(MonteCarloCollect, AggregatesAFixedSetOfRunFoldersAsCheckedByHand)
{
	esif::test::TempDir tmp;
	const std::string dir = campaignFolder(tmp, 3);
	// Run 1 (seed 1) and run 2 (seed 2) finished; run 3 failed.
	writeRunFolder(
		esif::campaign_layout::runFolder(dir, "ekf", 1),
		{pose(0, 0, 0, 0, std::nullopt), pose(1, 3, 4, 0.1, 2.0), pose(2, 0, 1, 0.0, 12.0)},
		{landmark(5, 0.3, 0.4, 1.0), landmark(9, 0, 0.2, 3.0)}, 1.0, 0);
	writeRunFolder(
		esif::campaign_layout::runFolder(dir, "ekf", 2),
		{pose(0, 0, 0, 0, std::nullopt), pose(1, 0, 0, -0.1, 4.0), pose(2, 0, 1, 0.0, 9.0)},
		{landmark(5, 0, 0, 5.0)}, 3.0, 2);
	esif::writeFailureRecord(
		esif::campaign_layout::failureFile(dir, "ekf", 3), {3, "esif: numerical failure: step 7: not PD", "..."});

	const esif::CampaignCollection c = esif::collectCampaign(dir, esif::CampaignPlan::load(dir));
	EXPECT_EQ(c.total, 3u);
	EXPECT_EQ(c.finished, 2u);
	ASSERT_EQ(c.gaps.failed.size(), 1u);
	EXPECT_EQ(c.gaps.failed[0], "ekf/seed_0003: failed (exit 3): esif: numerical failure: step 7: not PD");
	EXPECT_TRUE(c.gaps.pending.empty());
	ASSERT_EQ(c.configs.size(), 1u);
	const ConfigStatistics& s = c.configs[0];
	EXPECT_EQ(s.runs, 2u);
	ASSERT_EQ(s.steps.size(), 3u);
	// Step 0: no NEES (initial pose), errors zero.
	EXPECT_FALSE(s.steps[0].anees);
	EXPECT_EQ(s.steps[0].runs, 0u);
	// Step 1: ANEES (2 + 4) / 2 = 3 inside [chi2inv(.025, 6), chi2inv(.975, 6)] / 2
	// = [1.2373 / 2, 14.4494 / 2]; position errors 5 and 0: RMSE sqrt(25 / 2);
	// heading errors +-0.1: RMSE 0.1.
	EXPECT_DOUBLE_EQ(*s.steps[1].anees, 3.0);
	EXPECT_NEAR(s.steps[1].bounds.lo, 1.2373442 / 2, 1e-6);
	EXPECT_NEAR(s.steps[1].bounds.hi, 14.4493753 / 2, 1e-6);
	EXPECT_NEAR(s.steps[1].position_rmse_m, std::sqrt(12.5), 1e-12);
	EXPECT_NEAR(s.steps[1].heading_rmse_rad, 0.1, 1e-12);
	// p10 and p90 of {0, 5}, interpolated: 0.5 and 4.5.
	EXPECT_NEAR(s.steps[1].position_error_p10_m, 0.5, 1e-12);
	EXPECT_NEAR(s.steps[1].position_error_p90_m, 4.5, 1e-12);
	// Step 2: ANEES (12 + 9) / 2 = 10.5, above 7.2247: outside. One step of two inside.
	EXPECT_DOUBLE_EQ(*s.steps[2].anees, 10.5);
	EXPECT_DOUBLE_EQ(*s.pose_steps_inside_fraction, 0.5);
	EXPECT_DOUBLE_EQ(*s.pose_anees_mean, (3.0 + 10.5) / 2);
	// Landmarks: pairs (1, 3, 5): mean 3; landmark 5 ANEES (1 + 5) / 2 = 3
	// over 2 runs, landmark 9 ANEES 3 over 1 run (bounds [0.0506, 7.378]).
	EXPECT_DOUBLE_EQ(*s.landmark_anees, 3.0);
	ASSERT_EQ(s.landmarks.size(), 2u);
	EXPECT_EQ(s.landmarks[0].true_id, 5);
	EXPECT_EQ(s.landmarks[0].runs, 2u);
	EXPECT_DOUBLE_EQ(s.landmarks[0].anees, 3.0);
	EXPECT_NEAR(s.landmarks[0].rmse_m, std::sqrt(0.25 / 2), 1e-12);
	EXPECT_EQ(s.landmarks[1].runs, 1u);
	EXPECT_NEAR(s.landmarks[1].bounds.lo, 0.0506356, 1e-6);
	EXPECT_NEAR(s.landmarks[1].bounds.hi, 7.3777589, 1e-6);
	EXPECT_DOUBLE_EQ(*s.landmarks_inside_fraction, 1.0);
	// Trajectory RMSE per run: run 1 sqrt((0 + 25 + 1) / 3), run 2 sqrt(1 / 3).
	const double r1 = std::sqrt(26.0 / 3), r2 = std::sqrt(1.0 / 3);
	EXPECT_NEAR(s.trajectory_rmse_m.mean, (r1 + r2) / 2, 1e-12);
	EXPECT_NEAR(s.trajectory_rmse_m.stddev, std::abs(r1 - r2) / std::sqrt(2.0), 1e-12);
	// Landmark RMSE per run: run 1 sqrt((0.25 + 0.04) / 2), run 2 0.
	EXPECT_NEAR(s.landmark_rmse_m.mean, std::sqrt(0.29 / 2) / 2, 1e-12);
	EXPECT_DOUBLE_EQ(s.wall_s.median, 2.0);
	EXPECT_DOUBLE_EQ(s.wall_s.p25, 1.5);
	EXPECT_EQ(s.da_wrong_total, 2);
	EXPECT_EQ(s.runs_with_da_wrong, 1u);

	// The outputs are written and list the failed run.
	const std::string md = esif::writeCampaignOutputs(dir, esif::CampaignPlan::load(dir), c);
	EXPECT_NE(md.find("ekf/seed_0003: failed (exit 3)"), std::string::npos);
	for (const char* f : {"summary.csv", "summary.md", "summary.html", "per_step.csv", "landmarks.csv", "anees_pose.png", "rmse.png",
						  "landmark_anees.png"})
		EXPECT_TRUE(std::filesystem::is_regular_file(dir + "/" + f)) << f;
	const std::string csv = esif::test::readText(dir + "/summary.csv");
	EXPECT_NE(csv.find("\nekf,2,3,6.75,"), std::string::npos) << csv;
}

TEST(MonteCarloCollect, SplitsThePoseAneesIntoPositionAndHeadingAsCheckedByHand)
{
	esif::test::TempDir tmp;
	const std::string dir = campaignFolder(tmp, 2);
	// Heading NEES 9 and 7 at step 1: ANEES 8, above the 1-dof bound for 2
	// runs (chi2inv(.975, 2) / 2 = 3.689); position 1 and 3: 2, inside.
	// Step 2 has position NEES 4 in run 1 only (run 2 has none there).
	writeRunFolder(esif::campaign_layout::runFolder(dir, "ekf", 1),
				   {pose(1, 0, 0, 0, 10.0, 1.0, 9.0), pose(2, 0, 0, 0, 6.0, 4.0, 2.0)}, {}, 1.0, 0);
	writeRunFolder(esif::campaign_layout::runFolder(dir, "ekf", 2),
				   {pose(1, 0, 0, 0, 10.0, 3.0, 7.0), pose(2, 0, 0, 0, std::nullopt)}, {}, 1.0, 0);
	const esif::CampaignCollection c = esif::collectCampaign(dir, esif::CampaignPlan::load(dir));
	ASSERT_EQ(c.configs.size(), 1u);
	const ConfigStatistics& s = c.configs[0];
	ASSERT_EQ(s.steps.size(), 2u);
	EXPECT_DOUBLE_EQ(*s.steps[0].anees_position, 2.0);
	EXPECT_DOUBLE_EQ(*s.steps[0].anees_heading, 8.0);
	EXPECT_NEAR(s.steps[0].bounds_heading.hi, 7.3777589 / 2, 1e-6);
	EXPECT_FALSE(s.steps[0].bounds_heading.contains(*s.steps[0].anees_heading));
	EXPECT_TRUE(s.steps[0].bounds_position.contains(*s.steps[0].anees_position));
	EXPECT_DOUBLE_EQ(*s.steps[1].anees_position, 4.0);
	EXPECT_NEAR(s.steps[1].bounds_position.lo, esif::aneesBounds(2, 1).lo, 1e-15);
	EXPECT_DOUBLE_EQ(*s.pose_position_anees_mean, (2.0 + 4.0) / 2);
	EXPECT_DOUBLE_EQ(*s.pose_heading_anees_mean, (8.0 + 2.0) / 2);

	const std::string md = esif::writeCampaignOutputs(dir, esif::CampaignPlan::load(dir), c);
	EXPECT_NE(md.find("| 3 / 5 |"), std::string::npos) << md;
	const std::string per_step = esif::test::readText(dir + "/per_step.csv");
	// Step 1: position ANEES 2 with [chi2inv(.025, 4), chi2inv(.975, 4)] / 2 =
	// [0.2422, 5.5716], heading 8 with [chi2inv(.025, 2), chi2inv(.975, 2)] / 2.
	EXPECT_NE(per_step.find(",2,0.2422092785439"), std::string::npos) << per_step;
	EXPECT_NE(per_step.find(",8,0.0253178079842898"), std::string::npos) << per_step;
}

/// A run folder whose stats.json holds the map-scoring keys (`extra`: more JSON members).
void writeScoredRun(const std::string& dir, const std::string& extra)
{
	esif::ensureDirectory(dir);
	esif::writeEstimationErrorFiles(dir, {pose(1, 0, 0, 0, 1.0)}, {});
	esif::writeTextAtomically(dir + "/stats.json", "{\"wall_s\": 1, \"da_wrong\": 0" + extra + "}\n");
}

TEST(MonteCarloCollect, AggregatesTheMapScoresAsCheckedByHand)
{
	esif::test::TempDir tmp;
	const std::string dir = campaignFolder(tmp, 3);
	// Three draws: 16 true landmarks each; 16, 15, 16 found; duplicates 0, 2,
	// 1; one spurious landmark in run 3; precision 1, 0.9, 0.95; recall 0.99,
	// 0.8, 0.9; OSPA 0.1, 0.3, 0.2.
	const auto scores = [](int found, int dup, int spur, double precision, double recall, double ospa) {
		return ", \"landmarks_true\": 16, \"landmarks_found\": " + std::to_string(found) +
			   ", \"landmarks_duplicated\": " + std::to_string(dup) + ", \"landmarks_spurious\": " +
			   std::to_string(spur) + ", \"da_precision\": " + std::to_string(precision) +
			   ", \"da_recall\": " + std::to_string(recall) + ", \"landmark_ospa_m\": " + std::to_string(ospa);
	};
	writeScoredRun(esif::campaign_layout::runFolder(dir, "ekf", 1), scores(16, 0, 0, 1.0, 0.99, 0.1));
	writeScoredRun(esif::campaign_layout::runFolder(dir, "ekf", 2), scores(15, 2, 0, 0.9, 0.8, 0.3));
	writeScoredRun(esif::campaign_layout::runFolder(dir, "ekf", 3), scores(16, 1, 1, 0.95, 0.9, 0.2));
	const esif::CampaignCollection c = esif::collectCampaign(dir, esif::CampaignPlan::load(dir));
	ASSERT_EQ(c.configs.size(), 1u);
	const ConfigStatistics& s = c.configs[0];
	EXPECT_DOUBLE_EQ(*s.landmarks_true_median, 16.0);
	EXPECT_DOUBLE_EQ(*s.landmarks_found_median, 16.0);
	EXPECT_EQ(s.landmarks_duplicated_total, 3);
	EXPECT_EQ(s.runs_with_duplicated, 2u);
	EXPECT_EQ(s.landmarks_spurious_total, 1);
	EXPECT_EQ(s.runs_with_spurious, 1u);
	EXPECT_DOUBLE_EQ(s.da_precision->median, 0.95);
	EXPECT_DOUBLE_EQ(s.da_precision->min, 0.9);
	EXPECT_DOUBLE_EQ(s.da_recall->median, 0.9);
	EXPECT_DOUBLE_EQ(s.da_recall->min, 0.8);
	EXPECT_NEAR(s.landmark_ospa_m->mean, 0.2, 1e-12);
	EXPECT_NEAR(s.landmark_ospa_m->stddev, 0.1, 1e-12);
	const std::string md = esif::writeCampaignOutputs(dir, esif::CampaignPlan::load(dir), c);
	EXPECT_NE(md.find("| 16 / 16 | 3 in 2 runs / 1 in 1 runs | 0.95 [0.9] / 0.9 [0.8] | 0.2 ± 0.1 |"), std::string::npos)
		<< md;
	const std::string csv = esif::test::readText(dir + "/summary.csv");
	EXPECT_NE(csv.find(",16,16,3,2,1,1,0.94999999999999996,0.90000000000000002,0.90000000000000002,"
					   "0.80000000000000004,0.20000000000000004,"),
			  std::string::npos)
		<< csv;
}

TEST(MonteCarloCollect, RunsWithoutScoresLeaveThemEmptyAndBadScoresAreNamed)
{
	esif::test::TempDir tmp;
	const std::string dir = campaignFolder(tmp, 1);
	writeScoredRun(esif::campaign_layout::runFolder(dir, "ekf", 1), ", \"landmarks_true\": null");
	const ConfigStatistics s = esif::collectCampaign(dir, esif::CampaignPlan::load(dir)).configs.at(0);
	EXPECT_FALSE(s.landmarks_true_median);
	EXPECT_FALSE(s.da_precision);
	EXPECT_FALSE(s.landmark_ospa_m);
	EXPECT_NE(esif::monteCarloSummaryCells({s})[0].back(), "");
	const std::string run = tmp.file("bad");
	writeScoredRun(run, ", \"da_recall\": 1.5");
	try
	{
		esif::readCampaignRun(run, 0);
		FAIL() << "no error";
	}
	catch (const esif::InputError& e)
	{
		EXPECT_EQ(std::string(e.what()), run + "/stats.json: da_recall = 1.5 is outside [0, 1]");
	}
}

TEST(MonteCarloCollect, AMalformedErrorFileIsOneLineNamingIt)
{
	esif::test::TempDir tmp;
	const std::string run = tmp.file("run");
	writeRunFolder(run, {pose(1, 0, 0, 0, 1.0)}, {}, 1.0, 0);
	esif::writeTextAtomically(run + "/pose_errors.csv", "step,ex_m,ey_m,eth_rad,nees\n1,0,zero,0,1\n");
	try
	{
		esif::readCampaignRun(run, 0);
		FAIL() << "no error";
	}
	catch (const esif::InputError& e)
	{
		EXPECT_EQ(std::string(e.what()), run + "/pose_errors.csv:2: 'zero' is not a number");
	}
}

TEST(MonteCarloCollect, AFailureRecordIsReadStrictly)
{
	esif::test::TempDir tmp;
	const std::string path = tmp.file("failed.txt");
	esif::writeFailureRecord(path, {-3, "esif: error: x", "stderr\n"});
	const auto record = esif::readFailureRecord(path);
	EXPECT_EQ(record.exit_code, -3);
	EXPECT_EQ(record.error_line, "esif: error: x");
	// sscanf("exit_code = %d") read a code out of each of these.
	for (const char* first : {"exit_code = 3x", "exit_code = +3", "exit_code=3", "exit_code =  3", "exit_code = 3.0"})
	{
		esif::writeTextAtomically(path, std::string(first) + "\nerror = x\n--- stderr ---\n");
		try
		{
			esif::readFailureRecord(path);
			ADD_FAILURE() << "no error for '" << first << "'";
		}
		catch (const esif::InputError& e)
		{
			EXPECT_EQ(std::string(e.what()), path + ":1: expected 'exit_code = N'");
		}
	}
}

}  // namespace
