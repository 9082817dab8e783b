// The full-SLAM baseline on simulated data with ground truth: it is more
// accurate than EKF SLAM on the committed grid196 demo (it uses every
// measurement at every pose, the EKF only linearises once), its optimal cost
// has the chi-square value the noise model predicts, its covariances are
// consistent over independent runs, and re-solving during the run or
// starting from another run's estimate reaches the same optimum.

#include <EsifTestSupport.h>

#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/eval/Evaluator.h>
#include <esif/eval/StateNees.h>
#include <esif/formats/GroundTruth.h>
#include <esif/models/Se2.h>
#include <esif/run/InitialRun.h>
#include <esif/run/RunConfig.h>
#include <esif/sim/Simulator.h>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace
{
using namespace esif;
using test::pluginCounter;

const std::string kGrid196 = test::sourcePath("rawlogs/grid196.rawlog");

/// (chi2 - dof) / sqrt(2 dof): the optimal cost's distance from its
/// expectation in standard deviations of chi-square(dof).
double chi2Score(const FilterPlugin& p)
{
	const double dof = pluginCounter(p, "chi2_dof");
	return (pluginCounter(p, "chi2") - dof) / std::sqrt(2 * dof);
}

struct Scored
{
	FilterPlugin::Ptr plugin;
	ReplayResult result;
	Accuracy accuracy;
};

/// `[esif] initial_run = dir` read as the host reads it.
std::optional<InitialEstimate> initialRun(const std::string& dir)
{
	const auto cfg = ConfigFile::fromText("[esif]\nplugin = CeresFullSlam\ninitial_run = " + dir + "\n", "test.ini");
	return readInitialRun(cfg, loadHostParams(cfg));
}

Scored runOnGrid196(
	const std::string& plugin_class, const std::string& section, std::optional<InitialEstimate> start = std::nullopt)
{
	const Rawlog log = readRawlog(kGrid196);
	Scored s{test::makePlugin(plugin_class, section), {}, {}};
	if (start) s.plugin->setInitialEstimate(std::move(*start));
	s.result = replay(*s.plugin, log, {0, false});
	s.accuracy = test::scoreAgainstTruth(s.result, groundTruthPrefixFor(kGrid196));
	return s;
}

TEST(CeresFullGrid196, MoreAccurateThanEkfWithTheExpectedOptimalCost)
{
	const auto ekf = runOnGrid196("EkfSlam", "association = known_ids\n");
	const auto full = runOnGrid196("CeresFullSlam", "");
	const auto &a = full.accuracy, &e = ekf.accuracy;
	ASSERT_TRUE(a.landmark_rmse_m && e.landmark_rmse_m && a.ate_rmse_m && e.ate_rmse_m);
	std::cout << "grid196: landmark RMSE full SLAM " << *a.landmark_rmse_m << " m vs EKF " << *e.landmark_rmse_m
			  << " m; ATE " << *a.ate_rmse_m << " vs " << *e.ate_rmse_m << " m; landmark NEES mean "
			  << *a.landmark_nees_mean << ", consistent " << *a.landmark_consistent_fraction << "; chi2 "
			  << pluginCounter(*full.plugin, "chi2") << " for " << pluginCounter(*full.plugin, "chi2_dof") << " dof, "
			  << pluginCounter(*full.plugin, "iterations") << " iterations\n";
	EXPECT_EQ(pluginCounter(*full.plugin, "converged"), 1);
	EXPECT_EQ(a.landmarks_evaluated, e.landmarks_evaluated);
	EXPECT_LT(*a.landmark_rmse_m, *e.landmark_rmse_m);
	// The smoothed trajectory (every pose re-estimated with all data) against
	// the EKF's online one.
	EXPECT_LT(*a.ate_rmse_m, *e.ate_rmse_m);
	// 2 x cost at the optimum ~ chi-square(m - n) when the noise model is
	// right (the simulator's): 4 standard deviations leave a 6e-5 chance of
	// a false alarm; linearisation shifts it by far less than one.
	EXPECT_LT(std::abs(chi2Score(*full.plugin)), 4.0);
	// A single run's landmark errors share the trajectory's error, so their
	// mean NEES is close to one chi-square(2) draw; the consistency check
	// proper is the Monte Carlo test below. Here: at least 90 % of the
	// landmarks inside their 95 % ellipse.
	EXPECT_GE(*a.landmark_consistent_fraction, 0.90);
	// Pose 0 is the gauge; each of the 3000 steps (the first with a zero
	// increment and its noise) adds one.
	EXPECT_EQ(full.plugin->costFigures().poses_in_state, 3000u);
}

/// Truth in the frame of the true start pose (the estimate's frame).
Eigen::Vector2d inStartFrame(const Pose2& start, const Eigen::Vector2d& p)
{
	return inverseCompose(start, Pose2(p.x(), p.y(), 0)).head<2>();
}

TEST(CeresFullMonteCarlo, LandmarkAndFinalPoseNeesAreConsistentOverIndependentRuns)
{
	// The small scenario (16 features, 200 steps) with 20 seeds. Per run the
	// landmarks' NEES are correlated, but a mean of chi-square(2) variables
	// has at most their variance 4, so over 20 independent runs the grand
	// mean has standard deviation <= sqrt(4/20) = 0.45: 3 sigma gives
	// [0.66, 3.34] around 2. The final pose (3 dof, variance 6): [1.36, 4.64].
	const Scenario base = test::loadScenario("configs/sim/small.ini");
	const int runs = 20;
	double landmark_nees = 0, pose_nees = 0, chi2 = 0, dof = 0, state_nees = 0, state_dof = 0, map_nees = 0, map_dof = 0;
	for (int seed = 1; seed <= runs; ++seed)
	{
		Scenario s = base;
		s.seed = seed;
		const Simulator sim(s);
		auto plugin = test::makePlugin("CeresFullSlam", "");  // the default incremental schedule
		std::optional<Pose2> start;
		Pose2 last_true = Pose2::Zero();
		StateReference reference;
		sim.simulate(
			[&](const SimulatedStep& step)
			{
				if (!start) start = step.true_pose;
				last_true = step.true_pose;
				reference.poses_by_step[reference.poses_by_step.size()] = inverseCompose(*start, step.true_pose);
				plugin->processStep(step.input);
			});
		plugin->finish();
		for (std::size_t i = 0; i < sim.featureIds().size(); ++i)
			reference.landmarks[sim.featureIds()[i]] = inStartFrame(*start, sim.features()[i]);
		const auto whole = stateNees(*plugin->stateInformation(), reference, std::nullopt, "seed " + std::to_string(seed));
		ASSERT_TRUE(whole);
		EXPECT_EQ(whole->dof, 3 * reference.poses_by_step.size() + 2 * whole->landmarks_compared);  // every step's pose
		state_nees += whole->nees;
		state_dof += static_cast<double>(whole->dof);
		StateReference map_only = reference;
		map_only.poses_by_step.clear();	 // the poses marginalised (Schur complement)
		const auto map = stateNees(*plugin->stateInformation(), map_only, std::nullopt, "map of seed " + std::to_string(seed));
		ASSERT_TRUE(map);
		map_nees += map->nees;
		map_dof += static_cast<double>(map->dof);
		const Estimate est = plugin->estimate();
		double sum = 0;
		for (const auto& l : est.landmarks)
		{
			const auto i = std::find(sim.featureIds().begin(), sim.featureIds().end(), l.id) - sim.featureIds().begin();
			const Eigen::Vector2d err = l.mean - inStartFrame(*start, sim.features()[i]);
			sum += *nees(err, l.cov);
		}
		landmark_nees += sum / static_cast<double>(est.landmarks.size());
		Eigen::Vector3d pose_err = est.robot.mean - inverseCompose(*start, last_true);
		pose_err.z() = wrapAngle(pose_err.z());
		pose_nees += *nees(pose_err, est.robot.cov);
		chi2 += pluginCounter(*plugin, "chi2");
		dof += pluginCounter(*plugin, "chi2_dof");
	}
	landmark_nees /= runs;
	pose_nees /= runs;
	const double chi2_score = (chi2 - dof) / std::sqrt(2 * dof);
	const double state_score = (state_nees - state_dof) / std::sqrt(2 * state_dof);
	const double map_score = (map_nees - map_dof) / std::sqrt(2 * map_dof);
	std::cout << "whole-state NEES " << state_nees << " for " << state_dof << " dof (" << state_score
			  << " sigma); the map alone " << map_nees << " for " << map_dof << " dof (" << map_score << " sigma)\n";
	std::cout << runs << " runs: mean landmark NEES " << landmark_nees << " (2 expected), final pose NEES "
			  << pose_nees << " (3 expected), summed chi2 " << chi2 << " for " << dof << " dof (" << chi2_score
			  << " sigma)\n";
	EXPECT_GT(landmark_nees, 0.66);
	EXPECT_LT(landmark_nees, 3.34);
	EXPECT_GT(pose_nees, 1.36);
	EXPECT_LT(pose_nees, 4.64);
	EXPECT_LT(std::abs(chi2_score), 4.0);  // the sum over independent runs is chi-square(sum of dof)
	// The book's whole-state test of the map (every landmark jointly, the
	// poses marginalised): the same chi-square(sum of dof) argument.
	EXPECT_LT(std::abs(map_score), 4.0);
	// With every pose it is not (measured 1.49 per dof, 39 sigma; on the
	// committed grid196 draw 0.88, under-confident). Not understood yet: the
	// odometry's covariance is nearly singular across the path (two noises
	// drive three outputs), so the poses' NEES hangs on directions the
	// first-order model gets least right. Reported, not asserted.
}

/// Largest landmark position difference between `b` and the reference `a`,
/// in units of the reference's 1-sigma along its major axis.
double largestDifferenceInSigma(const Estimate& a, const Estimate& b)
{
	std::map<LandmarkId, const LandmarkEstimate*> ref;
	for (const auto& l : a.landmarks) ref[l.id] = &l;
	double worst = 0;
	for (const auto& l : b.landmarks)
	{
		const auto* r = ref.at(l.id);
		const double sigma = std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(r->cov).eigenvalues().maxCoeff());
		worst = std::max(worst, (r->mean - l.mean).norm() / sigma);
	}
	return worst;
}

// Ceres stops when an iteration lowers the cost by less than 1e-10 of it.
// Along the weakest direction (the map's rotation about the start) that
// leaves converged solutions up to ~1 mm apart at the same cost to 1e-9,
// measured at 0.001-0.003 of the landmarks' sigma. The tests allow 0.01.
constexpr double kSameOptimumSigma = 0.01;

TEST(CeresFullGrid196, ResolvingDuringTheRunReachesTheBatchOptimum)
{
	// grid196's odometry is precise enough for one batch solve from dead
	// reckoning to reach the optimum (its chi2 is checked above), so the
	// batch is the reference for both re-solve schedules.
	// finish() solves twice: with the Cauchy loss the run uses while it
	// looks for outliers (outliers = drop), then plainly (eq. 1.21).
	const auto batch = runOnGrid196("CeresFullSlam", "resolve_growth = 0\n");
	EXPECT_EQ(pluginCounter(*batch.plugin, "solves"), 2);
	EXPECT_EQ(pluginCounter(*batch.plugin, "outliers_dropped"), 0);
	const auto growing = runOnGrid196("CeresFullSlam", "covariance = none\n");	 // the default schedule
	const auto every = runOnGrid196("CeresFullSlam", "covariance = none\nresolve_growth = 0\nresolve_every_steps = 500\n");
	EXPECT_EQ(pluginCounter(*every.plugin, "solves"), 8);	 // after steps 500, ..., 3000, and finish()'s two
	// 3000 poses at 20 % growth from 20 new poses: 5 solves up to 100
	// poses, 18 of x1.2 up to 2685 (ln 30 / ln 1.2 = 18.7, each rounded
	// up), and finish()'s two.
	EXPECT_EQ(pluginCounter(*growing.plugin, "solves"), 25);
	for (const auto* running : {&growing, &every})
	{
		const double apart =
			largestDifferenceInSigma(batch.result.record.final_estimate, running->result.record.final_estimate);
		std::cout << pluginCounter(*running->plugin, "solves") << " solves, "
				  << pluginCounter(*running->plugin, "iterations")
				  << " iterations (batch: " << pluginCounter(*batch.plugin, "iterations") << "), landmarks within "
				  << apart << " sigma of the batch's\n";
		EXPECT_LT(apart, kSameOptimumSigma);
		const double chi2 = pluginCounter(*batch.plugin, "chi2");
		EXPECT_NEAR(pluginCounter(*running->plugin, "chi2"), chi2, 1e-6 * chi2);
		EXPECT_EQ(pluginCounter(*running->plugin, "converged"), 1);
		EXPECT_EQ(pluginCounter(*running->plugin, "optimum_plausible"), 1);
	}
}

TEST(CeresFullGrid196, StartingFromAnEkfRunReachesTheSameOptimum)
{
	test::TempDir dir;
	const auto ekf = test::runEsif(
		"run --quiet --config '" + test::sourcePath("configs/ekf.ini") + "' --rawlog '" + kGrid196 + "' --out '" +
		dir.file("ekf") + "'");
	ASSERT_EQ(ekf.exit_code, 0) << ekf.out;
	const auto batch = runOnGrid196("CeresFullSlam", "resolve_growth = 0\n");
	const auto warm =
		runOnGrid196("CeresFullSlam", "covariance = none\nresolve_growth = 0\n", initialRun(dir.file("ekf")));
	// The EKF's online trajectory does not fit the precise odometry (it jumps
	// at loop closures), so its start cost is not lower than dead
	// reckoning's; what matters is that it converges to the same optimum.
	const double apart = largestDifferenceInSigma(batch.result.record.final_estimate, warm.result.record.final_estimate);
	std::cout << "from the EKF's estimate: chi2 " << pluginCounter(*warm.plugin, "initial_chi2") << " -> "
			  << pluginCounter(*warm.plugin, "chi2") << " in " << pluginCounter(*warm.plugin, "iterations")
			  << " iterations (dead reckoning: " << pluginCounter(*batch.plugin, "initial_chi2") << " in "
			  << pluginCounter(*batch.plugin, "iterations") << "), landmarks within " << apart << " sigma\n";
	EXPECT_EQ(pluginCounter(*warm.plugin, "converged"), 1);
	const double chi2 = pluginCounter(*batch.plugin, "chi2");
	EXPECT_NEAR(pluginCounter(*warm.plugin, "chi2"), chi2, 1e-6 * chi2);
	EXPECT_LT(apart, kSameOptimumSigma);

	// A folder that is not a run is one clear error naming the key.
	try
	{
		initialRun(dir.file("nowhere"));
		FAIL() << "no error";
	}
	catch (const InputError& e)
	{
		EXPECT_NE(std::string(e.what()).find("initial_run"), std::string::npos) << e.what();
		EXPECT_NE(std::string(e.what()).find("run folder not found"), std::string::npos) << e.what();
	}
}

}  // namespace

namespace
{
/// The ConfigError configuring CeresFullSlam with `section` gives ("" for none).
std::string configError(const std::string& section)
{
	try
	{
		test::makePlugin("CeresFullSlam", section);
	}
	catch (const ConfigError& e)
	{
		return e.what();
	}
	return "";
}

TEST(CeresFullConfig, BoundsThatContradictEachOtherAreRefusedNotClamped)
{
	// Ceres would clamp a trust region whose largest radius is below its
	// first, or damping whose upper clamp is below its lower one: the run
	// would then use other values than the config says.
	EXPECT_NE(configError("initial_trust_region_radius = 100\nmax_trust_region_radius = 10\n")
				  .find("[ceres_full] max_trust_region_radius: 10 is below initial_trust_region_radius 100"),
			  std::string::npos);
	EXPECT_NE(configError("min_lm_diagonal = 2\nmax_lm_diagonal = 1\n")
				  .find("[ceres_full] max_lm_diagonal: 1 is below min_lm_diagonal 2"),
			  std::string::npos);
	EXPECT_EQ(configError("initial_trust_region_radius = 10\nmax_trust_region_radius = 10\n"), "");
	EXPECT_EQ(configError(""), "");
}
}  // namespace
