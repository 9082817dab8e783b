// The full-SLAM baseline's safeguards, end to end through the esif binary on
// the small simulated scenario (200 steps, 16 features): a wrong noise model
// is flagged as an implausible optimum, a solution with a pose on a landmark
// is flagged as degenerate and still finishes with every output written and
// its covariances marked absent, and a robust loss resists outliers and is
// named in the run's stats.

#include <EsifTestSupport.h>

#include <esif/formats/RawlogReader.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/formats/StatsJson.h>
#include <esif/models/Se2.h>
#include <esif/sim/Simulator.h>

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

namespace
{
using namespace esif;

struct RunResult
{
	test::CommandResult command;
	Stats stats;
};

RunResult runEsif(const std::string& ini_text, const std::string& rawlog, const std::string& out, const test::TempDir& dir)
{
	const std::string ini = out + ".ini";
	std::ofstream(ini) << ini_text;
	RunResult r;
	r.command = test::runEsif("run --quiet --config '" + ini + "' --rawlog '" + rawlog + "' --out '" + out + "'");
	EXPECT_EQ(r.command.exit_code, 0) << r.command.out;
	if (std::filesystem::exists(out + "/stats.json"))
		r.stats = Stats::load(out + "/stats.json");
	return r;
}

std::size_t lineCount(const std::string& text) { return std::count(text.begin(), text.end(), '\n'); }

/// Lines of the plugin's own warnings.
std::size_t warningCount(const std::string& text)
{
	std::size_t n = 0;
	for (std::size_t at = text.find("esif: warning: ceres_full: "); at != std::string::npos;
		 at = text.find("esif: warning: ceres_full: ", at + 1))
		++n;
	return n;
}

std::string simulatedSmall(const test::TempDir& dir)
{
	const std::string rawlog = dir.file("small.rawlog");
	const auto sim = test::simulateSmall(rawlog);
	EXPECT_EQ(sim.exit_code, 0) << sim.out;
	return rawlog;
}

TEST(CeresFullSafeguards, TheRightNoiseModelGivesAPlausibleOptimumWithCovariances)
{
	test::TempDir dir;
	const auto rawlog = simulatedSmall(dir);
	const RunResult r = runEsif("[esif]\nplugin = CeresFullSlam\n", rawlog, dir.file("plain"), dir);
	EXPECT_EQ(lineCount(r.command.out), 0u) << r.command.out;  // --quiet and nothing to warn about
	EXPECT_EQ(test::statNumber(r.stats, "plugin_optimum_plausible"), 1);
	EXPECT_EQ(test::statNumber(r.stats, "plugin_degenerate_poses"), 0);
	EXPECT_EQ(test::statNumber(r.stats, "plugin_covariances_available"), 1);
	EXPECT_EQ(test::statNumber(r.stats, "plugin_robust_loss_used"), 0);
	// The simulator draws the noise it declares: chi2 / dof ~ 1 within
	// sqrt(2 / dof) per sigma; dof ~ 1000 here, so 4 sigma is 0.18.
	EXPECT_NEAR(test::statNumber(r.stats, "plugin_chi2_per_dof"), 1.0, 0.2);
	EXPECT_TRUE(r.stats.number("landmark_nees_mean").has_value());
}

TEST(CeresFullSafeguards, AnOverconfidentNoiseModelIsFlaggedAsAnImplausibleOptimum)
{
	// Declaring the sensor 10x more precise than it is (0.01 m, 0.1 deg
	// against the simulator's 0.1 m, 1 deg) multiplies the measurement terms
	// of chi2 by 100: chi2 / dof far above max_chi2_per_dof = 3.
	test::TempDir dir;
	const auto rawlog = simulatedSmall(dir);
	const RunResult r = runEsif(
		"[esif]\nplugin = CeresFullSlam\nsensor_std_range_m = 0.01\nsensor_std_bearing_deg = 0.1\n", rawlog,
		dir.file("tight"), dir);
	EXPECT_GT(test::statNumber(r.stats, "plugin_chi2_per_dof"), 10);
	EXPECT_EQ(test::statNumber(r.stats, "plugin_optimum_plausible"), 0);
	EXPECT_EQ(test::statNumber(r.stats, "plugin_degenerate_poses"), 0);
	EXPECT_NE(r.command.out.find("implausible optimum"), std::string::npos) << r.command.out;
	EXPECT_NE(r.command.out.find("max_chi2_per_dof"), std::string::npos) << r.command.out;
	// Scored against the simulator's truth, covariances 100 times too small
	// give landmarks a mean NEES far above 100: the run is suspect as well,
	// one line each.
	EXPECT_EQ(lineCount(r.command.out), 2u) << r.command.out;
	EXPECT_EQ(test::statNumber(r.stats, "suspect"), 1);
	EXPECT_NE(r.command.out.find("mean landmark NEES"), std::string::npos) << r.command.out;
}

std::string shortest(double v)
{
	char buf[32];
	const auto r = std::to_chars(buf, buf + sizeof(buf), v);
	return std::string(buf, r.ptr);
}

/// Rewrites run folder `dir`'s landmarks.txt with landmark `id` exactly at
/// (x, y) and no covariance.
void moveLandmark(const std::string& dir, LandmarkId id, double x, double y)
{
	const auto landmarks = readLandmarksTxt(dir + "/landmarks.txt");
	std::ofstream out(dir + "/landmarks.txt");
	out << "# id x y cxx cxy cyy\n";
	for (const auto& l : landmarks)
	{
		const bool moved = l.id == id;
		out << l.id << ' ' << shortest(moved ? x : l.mean.x()) << ' ' << shortest(moved ? y : l.mean.y())
			<< " 0 0 0\n";
	}
}

TEST(CeresFullSafeguards, APoseOnALandmarkIsFlaggedAndTheRunStillWritesEveryOutputWithoutCovariances)
{
	// The collapsed solution of the issue: a pose exactly on a landmark it
	// measured metres away. Started there (initial_run = a good run with
	// that landmark moved onto the pose), the range and bearing terms have
	// no derivative, so neither the solve nor the covariances can proceed;
	// the run must still finish, write its outputs and say what happened.
	test::TempDir dir;
	const auto rawlog = simulatedSmall(dir);
	runEsif("[esif]\nplugin = CeresFullSlam\n", rawlog, dir.file("good"), dir);

	// The first measurement taken further than 1 m away, at step k.
	const Rawlog log = readRawlog(rawlog);
	std::size_t k = 0;
	std::optional<LandmarkId> id;
	for (; k < log.steps.size() && !id; ++k)
		if (log.steps[k].scan)
			for (const auto& m : log.steps[k].scan->measurements)
				if (m.range_m > 1 && m.id && !id) id = m.id;
	ASSERT_TRUE(id.has_value());
	--k;
	ASSERT_EQ(log.steps[k].scan->sensor_on_robot, Pose2::Zero());	// the sensor is the robot's origin
	const auto trajectory = readTrajectoryTum(dir.file("good") + "/trajectory.tum");
	moveLandmark(dir.file("good"), *id, trajectory[k].pose.x, trajectory[k].pose.y);

	const std::string out = dir.file("collapsed");
	const RunResult r = runEsif(
		"[esif]\nplugin = CeresFullSlam\ninitial_run = " + dir.file("good") + "\n", rawlog, out, dir);
	EXPECT_EQ(test::statNumber(r.stats, "plugin_degenerate_poses"), 1);
	EXPECT_EQ(test::statNumber(r.stats, "plugin_optimum_plausible"), 0);
	EXPECT_EQ(test::statNumber(r.stats, "plugin_covariances_available"), 0);
	EXPECT_EQ(test::statNumber(r.stats, "plugin_converged"), 0);
	// One line each: the failed final solve, the implausible optimum, the
	// covariances; nothing else (glog and SuiteSparse are held back).
	EXPECT_EQ(warningCount(r.command.out), 3u) << r.command.out;
	EXPECT_EQ(lineCount(r.command.out), 3u) << r.command.out;
	EXPECT_EQ(r.command.out.find("Logging before InitGoogleLogging"), std::string::npos) << r.command.out;
	EXPECT_NE(r.command.out.find("1 pose(s) on a landmark"), std::string::npos) << r.command.out;
	EXPECT_NE(r.command.out.find("without covariances"), std::string::npos) << r.command.out;
	// Every output of a normal run is there, and the NEES metrics are absent,
	// not computed from zero covariances.
	// (Except the information matrix's picture and its SVG: J has no finite value there.)
	for (const auto& entry : std::filesystem::directory_iterator(dir.file("good")))
	{
		if (entry.path().stem() != "info_matrix")
		{
			EXPECT_TRUE(std::filesystem::exists(out + "/" + entry.path().filename().string())) << entry.path();
		}
	}
	EXPECT_FALSE(r.stats.number("landmark_nees_mean").has_value());
	EXPECT_FALSE(r.stats.number("pose_nees_mean").has_value());
	EXPECT_FALSE(r.stats.number("landmark_consistent_fraction").has_value());
	EXPECT_TRUE(r.stats.number("landmark_rmse_m").has_value());
	for (const auto& l : readLandmarksTxt(out + "/landmarks.txt")) EXPECT_TRUE(l.cov.isZero(0)) << l.id;
}

/// Landmark RMSE [m] of a plugin fed the small scenario with every 10th
/// re-observation's range made 3 m too long (a gross outlier: 30 sigma).
/// First sightings are left clean: an outlier there starts its landmark 3 m
/// off, where a redescending loss (Cauchy) then discounts every correct
/// measurement of it and cannot recover (the convex Huber loss can).
double landmarkRmseWithOutliers(const std::string& section, double* robust_loss_used)
{
	Scenario s = test::loadScenario("configs/sim/small.ini");
	const Simulator sim(s);
	auto plugin = test::makePlugin("CeresFullSlam", section);
	std::optional<Pose2> start;
	std::size_t count = 0;
	std::set<LandmarkId> seen;
	sim.simulate(
		[&](const SimulatedStep& step)
		{
			if (!start) start = step.true_pose;
			StepInput input = step.input;
			if (input.scan)
				for (auto& m : input.scan->measurements)
					if (!seen.insert(*m.id).second && ++count % 10 == 0) m.range_m += 3.0;
			plugin->processStep(input);
		});
	plugin->finish();
	for (const auto& [k, v] : plugin->costFigures().counters)
		if (k == "robust_loss_used") *robust_loss_used = v;
	double sq = 0;
	const Estimate e = plugin->estimate();
	for (const auto& l : e.landmarks)
	{
		const auto i = std::find(sim.featureIds().begin(), sim.featureIds().end(), l.id) - sim.featureIds().begin();
		const Eigen::Vector2d truth = inverseCompose(*start, Pose2(sim.features()[i].x(), sim.features()[i].y(), 0)).head<2>();
		sq += (l.mean - truth).squaredNorm();
	}
	return std::sqrt(sq / static_cast<double>(e.landmarks.size()));
}

TEST(CeresFullSafeguards, ACauchyLossResistsOutliersAndIsNamedInTheStats)
{
	double plain_used = -1, huber_used = -1, cauchy_used = -1;
	// outliers = keep: the plain least squares the losses are compared with
	// (the default drops the outliers, below).
	const double plain = landmarkRmseWithOutliers("covariance = none\noutliers = keep\n", &plain_used);
	const double huber = landmarkRmseWithOutliers("covariance = none\nrobust_loss = huber\n", &huber_used);
	const double cauchy = landmarkRmseWithOutliers("covariance = none\nrobust_loss = cauchy\n", &cauchy_used);
	std::cout << "landmark RMSE with 10 % outliers: none " << plain << " m, huber " << huber << " m, cauchy " << cauchy
			  << " m\n";
	EXPECT_EQ(plain_used, 0);
	EXPECT_EQ(huber_used, 1);
	EXPECT_EQ(cauchy_used, 2);
	// Without outliers the landmarks are within ~0.05 m here (0.1 m range
	// noise, many sightings each); 10 % of 3 m outliers pull the plain
	// solution by decimetres. Both losses bound the outliers' influence
	// (Cauchy's vanishes), so each must at least halve the error.
	EXPECT_LT(cauchy, 0.5 * plain);
	EXPECT_LT(huber, 0.5 * plain);

	// Through the binary: the stats name the loss.
	test::TempDir dir;
	const auto rawlog = simulatedSmall(dir);
	const RunResult r = runEsif(
		"[esif]\nplugin = CeresFullSlam\n[ceres_full]\nrobust_loss = cauchy\n", rawlog, dir.file("cauchy"), dir);
	EXPECT_EQ(test::statNumber(r.stats, "plugin_robust_loss_used"), 2);
	EXPECT_EQ(test::statNumber(r.stats, "plugin_converged"), 1);
	EXPECT_EQ(test::statNumber(r.stats, "plugin_optimum_plausible"), 1);
}

}  // namespace
