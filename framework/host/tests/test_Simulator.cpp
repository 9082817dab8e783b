/// \file test_Simulator.cpp
/// The simulator behind `esif simulate`: determinism, measurement and
/// odometry statistics against the ground truth, and an MRPT-readable rawlog.

#include <esif/config/ConfigFile.h>
#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/formats/GroundTruth.h>
#include <esif/models/Se2.h>
#include <esif/sim/Scenario.h>
#include <esif/sim/Simulator.h>

#include <mrpt/core/Clock.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <set>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using namespace esif;

namespace
{
const std::string kSmallIni = std::string(ESIF_SOURCE_DIR) + "/configs/sim/small.ini";

Scenario loadScenario(const std::string& path) { return Scenario::fromConfig(ConfigFile::load(path)); }

Scenario scenarioFromText(const std::string& text)
{
	Scenario s;
	loadParams(s, ConfigFile::fromText(text, "test.ini").section("simulation"));
	return s;
}

/// A fresh folder for one test's outputs, removed afterwards.
class TempDir
{
   public:
	explicit TempDir(const std::string& name)
		: path_(fs::temp_directory_path() / ("esif_test_sim_" + name + "_" + std::to_string(::getpid())))
	{
		fs::remove_all(path_);
		fs::create_directories(path_);
	}
	~TempDir() { fs::remove_all(path_); }
	std::string file(const std::string& name) const { return (path_ / name).string(); }

   private:
	fs::path path_;
};

std::string readBytes(const std::string& path)
{
	std::ifstream in(path, std::ios::binary);
	return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The rawlog's (action, observation) pairs, read back with MRPT.
struct Reloaded
{
	std::vector<mrpt::obs::CActionRobotMovement2D::Ptr> moves;
	std::vector<mrpt::obs::CObservationBearingRange::Ptr> scans;
};

Reloaded reload(const std::string& path)
{
	mrpt::obs::CRawlog rawlog;
	EXPECT_TRUE(rawlog.loadFromRawLogFile(path));
	Reloaded out;
	for (std::size_t i = 0; i < rawlog.size(); ++i)
	{
		// Strict alternation: action collection, then sensory frame.
		if (i % 2 == 0)
		{
			EXPECT_EQ(rawlog.getType(i), mrpt::obs::CRawlog::etActionCollection) << "entry " << i;
			const auto acts = rawlog.getAsAction(i);
			EXPECT_EQ(acts->size(), 1u);
			out.moves.push_back(acts->getActionByClass<mrpt::obs::CActionRobotMovement2D>());
			EXPECT_TRUE(out.moves.back()) << "entry " << i;
		}
		else
		{
			EXPECT_EQ(rawlog.getType(i), mrpt::obs::CRawlog::etSensoryFrame) << "entry " << i;
			const auto sf = rawlog.getAsObservations(i);
			EXPECT_EQ(sf->size(), 1u);
			out.scans.push_back(sf->getObservationByClass<mrpt::obs::CObservationBearingRange>());
			EXPECT_TRUE(out.scans.back()) << "entry " << i;
		}
	}
	return out;
}
}  // namespace

TEST(Simulator, DefaultsAndCommittedConfigsAreValid)
{
	EXPECT_NO_THROW(Simulator(Scenario{}));
	for (const char* name : {"small", "grid196", "grid1225", "grid1225_large", "city", "city_60k", "city_30k", "city_10k", "city_1k"})
	{
		SCOPED_TRACE(name);
		Scenario s;
		ASSERT_NO_THROW(s = loadScenario(std::string(ESIF_SOURCE_DIR) + "/configs/sim/" + name + ".ini"));
		EXPECT_NO_THROW(s.validate());
	}
}

/// The city family is one world and one tour cut at different lengths (the
/// growth curves of docs/results compare them): every key but `steps` equal.
TEST(Simulator, CityConfigsDifferOnlyInTheirSteps)
{
	const auto keysButSteps = [](const std::string& name) {
		std::ifstream in(std::string(ESIF_SOURCE_DIR) + "/configs/sim/" + name + ".ini");
		std::string line, kept;
		while (std::getline(in, line))
			if (!line.empty() && line[0] != ';' && line[0] != '#' && line.rfind("steps", 0) != 0) kept += line + "\n";
		return kept;
	};
	const std::string city = keysButSteps("city");
	EXPECT_NE(city.find("features_per_side"), std::string::npos);
	EXPECT_EQ(keysButSteps("city_10k"), city);
	EXPECT_EQ(keysButSteps("city_60k"), city);
	EXPECT_EQ(keysButSteps("city_30k"), city);
	EXPECT_EQ(keysButSteps("city_1k"), city);
}

TEST(Simulator, BadValuesAreConfigErrors)
{
	EXPECT_THROW(scenarioFromText("[simulation]\ndt_s = 0\n"), ConfigError);
	EXPECT_THROW(scenarioFromText("[simulation]\nsteps = 0\n"), ConfigError);
	EXPECT_THROW(scenarioFromText("[simulation]\nsensor_fov_deg = 400\n"), ConfigError);
	EXPECT_THROW(scenarioFromText("[simulation]\nstd_range_m = -0.1\n"), ConfigError);
	EXPECT_THROW(scenarioFromText("[simulation]\nspeed_mps = fast\n"), ConfigError);

	// Rules across fields, checked by the simulator itself.
	Scenario outside;
	outside.start_x_m = outside.world_size_m + 1;
	EXPECT_THROW(Simulator{outside}, ConfigError);
	Scenario no_waypoint_area;
	no_waypoint_area.waypoint_margin_m = no_waypoint_area.world_size_m / 2;
	try
	{
		Simulator{no_waypoint_area};
		FAIL() << "expected ConfigError";
	}
	catch (const ConfigError& e)
	{
		EXPECT_NE(std::string(e.what()).find("waypoint_margin_m"), std::string::npos) << e.what();
	}
}

TEST(Simulator, FeaturesFormTheGridWithHalfSpacingMargin)
{
	const Scenario s = loadScenario(kSmallIni);
	const Simulator sim(s);
	const int n = s.features_per_side;
	ASSERT_EQ(sim.features().size(), static_cast<std::size_t>(n * n));
	const double spacing = s.world_size_m / n;
	// ID = row * n + column, from the bottom-left feature.
	EXPECT_NEAR(sim.features()[0].x(), spacing / 2, 1e-12);
	EXPECT_NEAR(sim.features()[0].y(), spacing / 2, 1e-12);
	EXPECT_NEAR(sim.features()[1].x(), 1.5 * spacing, 1e-12);
	EXPECT_NEAR(sim.features()[n].y(), 1.5 * spacing, 1e-12);
	EXPECT_NEAR(sim.features().back().x(), s.world_size_m - spacing / 2, 1e-12);
	EXPECT_NEAR(sim.features().back().y(), s.world_size_m - spacing / 2, 1e-12);
}

TEST(Simulator, SameSeedGivesByteIdenticalOutputs)
{
	TempDir dir("determinism");
	const Scenario s = loadScenario(kSmallIni);
	const SimulationSummary a = Simulator(s).writeRawlog(dir.file("a.rawlog"));
	const SimulationSummary b = Simulator(s).writeRawlog(dir.file("b.rawlog"));
	const std::string bytes = readBytes(dir.file("a.rawlog"));
	ASSERT_FALSE(bytes.empty());
	EXPECT_EQ(bytes, readBytes(dir.file("b.rawlog")));
	EXPECT_EQ(readBytes(dir.file("a_ground_truth_robot_path.txt")), readBytes(dir.file("b_ground_truth_robot_path.txt")));
	EXPECT_EQ(readBytes(dir.file("a_ground_truth.txt")), readBytes(dir.file("b_ground_truth.txt")));
	EXPECT_EQ(a.measurements, b.measurements);

	Scenario other = s;
	other.seed = s.seed + 1;
	Simulator(other).writeRawlog(dir.file("c.rawlog"));
	EXPECT_NE(bytes, readBytes(dir.file("c.rawlog")));
	EXPECT_NE(readBytes(dir.file("a_ground_truth_robot_path.txt")), readBytes(dir.file("c_ground_truth_robot_path.txt")));
}

TEST(Simulator, NoiseSeedRedrawsTheNoiseOnTheSamePath)
{
	// A Monte Carlo campaign's runs: same world and true path, new noise.
	TempDir dir("noise_seed");
	const Scenario s = loadScenario(kSmallIni);
	Simulator(s).writeRawlog(dir.file("a.rawlog"));
	Scenario same = s;
	same.noise_seed = s.seed;  // explicitly what -1 derives: byte-identical
	Simulator(same).writeRawlog(dir.file("b.rawlog"));
	EXPECT_EQ(readBytes(dir.file("a.rawlog")), readBytes(dir.file("b.rawlog")));
	Scenario other = s;
	other.noise_seed = s.seed + 1;
	Simulator(other).writeRawlog(dir.file("c.rawlog"));
	EXPECT_NE(readBytes(dir.file("a.rawlog")), readBytes(dir.file("c.rawlog")));
	EXPECT_EQ(readBytes(dir.file("a_ground_truth_robot_path.txt")), readBytes(dir.file("c_ground_truth_robot_path.txt")));
	EXPECT_EQ(readBytes(dir.file("a_ground_truth.txt")), readBytes(dir.file("c_ground_truth.txt")));
}

TEST(Simulator, RawlogReloadsWithMrptAsWritten)
{
	TempDir dir("reload");
	const Scenario s = loadScenario(kSmallIni);
	const SimulationSummary summary = Simulator(s).writeRawlog(dir.file("small.rawlog"));
	EXPECT_EQ(summary.steps, static_cast<std::size_t>(s.steps));
	std::vector<SimulatedStep> steps;
	Simulator(s).simulate([&](const SimulatedStep& step) { steps.push_back(step); });

	const Reloaded log = reload(dir.file("small.rawlog"));
	ASSERT_EQ(log.moves.size(), static_cast<std::size_t>(s.steps));
	ASSERT_EQ(log.scans.size(), static_cast<std::size_t>(s.steps));

	// Step 0 is a zero move with a tiny covariance, so the first scan (taken
	// at the start pose) survives MRPT's action/sensory-frame pairing.
	const auto [cov0, mean0] = log.moves[0]->poseChange->getCovarianceAndMean();
	EXPECT_EQ(mean0.x(), 0.0);
	EXPECT_EQ(mean0.y(), 0.0);
	EXPECT_EQ(mean0.phi(), 0.0);
	EXPECT_LT(cov0.maxCoeff(), 1e-8);

	std::size_t measurements = 0;
	std::set<int> ids;
	for (std::size_t k = 0; k < log.scans.size(); ++k)
	{
		const auto& move = *log.moves[k];
		const auto& obs = *log.scans[k];
		// Stored as a PDF, not as emOdometry (which MRPT re-derives from its own model).
		EXPECT_EQ(move.estimationMethod, mrpt::obs::CActionRobotMovement2D::emScan2DMatching);
		EXPECT_NEAR(mrpt::Clock::toDouble(move.timestamp), k * s.dt_s, 1e-6);
		EXPECT_NEAR(mrpt::Clock::toDouble(obs.timestamp), k * s.dt_s, 1e-6);
		const auto [cov, mean] = move.poseChange->getCovarianceAndMean();
		EXPECT_EQ(toPose2(mean.asTPose()), steps[k].input.odometry->delta) << "step " << k;
		EXPECT_EQ(Eigen::Matrix3d(cov.asEigen()), steps[k].input.odometry->cov) << "step " << k;
		EXPECT_EQ(Eigen::Matrix3d(cov.asEigen()).llt().info(), Eigen::Success) << "step " << k;
		EXPECT_FALSE(obs.validCovariances);
		EXPECT_FLOAT_EQ(obs.maxSensorDistance, s.sensor_max_range_m);
		EXPECT_FLOAT_EQ(obs.fieldOfView_yaw, s.sensor_fov_deg * M_PI / 180);
		EXPECT_FLOAT_EQ(obs.sensor_std_range, s.std_range_m);
		EXPECT_FLOAT_EQ(obs.sensor_std_yaw, s.std_bearing_deg * M_PI / 180);
		measurements += obs.sensedData.size();
		for (const auto& m : obs.sensedData) ids.insert(m.landmarkID);
	}
	EXPECT_EQ(measurements, summary.measurements);
	EXPECT_EQ(ids.size(), summary.features_seen);
	EXPECT_GT(summary.features_seen, 0u);

	const auto truth = loadGroundTruth(groundTruthPrefixFor(dir.file("small.rawlog")));
	ASSERT_TRUE(truth);
	EXPECT_EQ(truth->path.size(), static_cast<std::size_t>(s.steps));
	EXPECT_EQ(truth->landmarks.size(), summary.features);
	EXPECT_NEAR(truth->path[0].x(), s.start_x_m, 1e-12);
	EXPECT_NEAR(truth->path[0].y(), s.start_y_m, 1e-12);
}

/// Every measurement is of a feature within range and field of view of the
/// TRUE sensor pose (from the ground-truth files), within 5 sigma of the true
/// range and bearing; and every such feature is measured.
TEST(Simulator, MeasurementsMatchGroundTruth)
{
	TempDir dir("measurements");
	Scenario s = loadScenario(kSmallIni);
	s.steps = 1000;
	Simulator(s).writeRawlog(dir.file("m.rawlog"));
	const Reloaded log = reload(dir.file("m.rawlog"));
	const auto truth = loadGroundTruth(groundTruthPrefixFor(dir.file("m.rawlog")));
	ASSERT_TRUE(truth);
	ASSERT_EQ(truth->path.size(), log.scans.size());

	const double std_bearing = s.std_bearing_deg * M_PI / 180;
	const double half_fov = s.sensor_fov_deg * M_PI / 180 / 2;
	// The rawlog stores ranges and bearings as float: allow for the rounding.
	const double float_eps = 1e-5;
	std::size_t checked = 0;
	for (std::size_t k = 0; k < log.scans.size(); ++k)
	{
		const auto& obs = *log.scans[k];
		const mrpt::poses::CPose2D on_robot(obs.sensorLocationOnRobot);
		const Pose2 sensor = compose(truth->path[k], Pose2(on_robot.x(), on_robot.y(), on_robot.phi()));
		std::set<LandmarkId> measured;
		for (const auto& m : obs.sensedData)
		{
			ASSERT_TRUE(truth->landmarks.count(m.landmarkID)) << "unknown ID " << m.landmarkID;
			const Eigen::Vector2d& f = truth->landmarks.at(m.landmarkID);
			const Eigen::Vector2d p = inverseCompose(sensor, Pose2(f.x(), f.y(), 0)).head<2>();
			const double range = p.norm(), bearing = std::atan2(p.y(), p.x());
			EXPECT_LE(range, s.sensor_max_range_m) << "step " << k << " ID " << m.landmarkID;
			EXPECT_LE(std::abs(bearing), half_fov) << "step " << k << " ID " << m.landmarkID;
			EXPECT_GE(m.range, 0.0f);
			EXPECT_LE(std::abs(m.range - range), 5 * s.std_range_m + float_eps) << "step " << k;
			EXPECT_LE(std::abs(wrapAngle(m.yaw - bearing)), 5 * std_bearing + float_eps) << "step " << k;
			EXPECT_GT(m.yaw, -M_PI - float_eps);
			EXPECT_LE(m.yaw, M_PI + float_eps);
			EXPECT_EQ(m.pitch, 0.0f);
			measured.insert(m.landmarkID);
			++checked;
		}
		EXPECT_EQ(measured.size(), obs.sensedData.size()) << "a feature measured twice at step " << k;
		// Completeness, away from the visibility boundary where the float
		// rounding of the stored poses could flip the decision.
		for (const auto& [id, f] : truth->landmarks)
		{
			const Eigen::Vector2d p = inverseCompose(sensor, Pose2(f.x(), f.y(), 0)).head<2>();
			if (p.norm() < s.sensor_max_range_m - 1e-6 && std::abs(std::atan2(p.y(), p.x())) < half_fov - 1e-6)
			{
				EXPECT_TRUE(measured.count(id)) << "step " << k << ": visible feature " << id << " not measured";
			}
		}
	}
	EXPECT_GT(checked, 1000u);
}

/// The odometry increments are consistent with the true path: with
/// e = reported increment - true increment (pose k-1 to pose k), the
/// normalised squared errors follow the chi-square distribution the
/// reported covariances promise.
TEST(Simulator, OdometryIsConsistentWithTruePath)
{
	Scenario s = loadScenario(kSmallIni);
	s.steps = 4001;
	std::vector<SimulatedStep> steps;
	Simulator(s).simulate([&](const SimulatedStep& step) { steps.push_back(step); });
	ASSERT_EQ(steps.size(), static_cast<std::size_t>(s.steps));

	double nees2 = 0, nees3 = 0;
	Eigen::Vector3d mean_error = Eigen::Vector3d::Zero();
	const std::size_t n = steps.size() - 1;
	for (std::size_t k = 1; k < steps.size(); ++k)
	{
		const OdometryIncrement& odo = *steps[k].input.odometry;
		const Pose2 truth = inverseCompose(steps[k - 1].true_pose, steps[k].true_pose);
		Eigen::Vector3d e = odo.delta - truth;
		e.z() = wrapAngle(e.z());
		mean_error += e / n;
		nees3 += e.dot(odo.cov.ldlt().solve(e)) / n;
		// Two noises (speed, turn rate) drive the three components: to first
		// order the error lies in the covariance's two-dimensional dominant
		// subspace and is exactly chi-square with 2 dof there.
		const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(odo.cov);
		for (int i = 1; i < 3; ++i) nees2 += std::pow(eig.eigenvectors().col(i).dot(e), 2) / eig.eigenvalues()(i) / n;
	}
	// Steps are independent, so n * nees2 ~ chi2(2n): mean 2, standard
	// deviation sqrt(4 / n) = 0.032 for n = 4000. A band of +-4 sigma
	// (two-sided probability 6e-5 of a false failure for an arbitrary seed)
	// is [1.87, 2.13]; a covariance off by 10 % would fail it.
	const double sigma2 = std::sqrt(4.0 / n);
	EXPECT_NEAR(nees2, 2.0, 4 * sigma2);
	// The full 3-dof statistic adds the weak third direction (second-order
	// error n_speed * n_turn against the covariance floor); it must not
	// exceed chi2(3)'s mean of 3: per-step variance is at most 2 + 2 + 8
	// (the product of two unit normals squared has variance 8).
	EXPECT_LT(nees3, 3.0 + 4 * std::sqrt(12.0 / n));
	EXPECT_GT(nees3, 2.0 - 4 * sigma2);
	// No bias: each mean component within 4 standard errors of zero.
	const double std_d = s.std_speed_mps * s.dt_s;
	EXPECT_LT(std::abs(mean_error.x()), 4 * std_d / std::sqrt(double(n)));
	EXPECT_LT(std::abs(mean_error.z()), 4 * s.std_turn_rate_deg_s * M_PI / 180 * s.dt_s / std::sqrt(double(n)));
}

TEST(Simulator, SimulateIsRepeatableAndMatchesSummary)
{
	const Scenario s = loadScenario(kSmallIni);
	const Simulator sim(s);
	std::vector<Pose2> first, second;
	std::size_t measurements = 0;
	const SimulationSummary summary = sim.simulate([&](const SimulatedStep& step) {
		first.push_back(step.true_pose);
		measurements += step.input.scan->measurements.size();
		EXPECT_NEAR(step.input.time_s, step.input.index * s.dt_s, 1e-12);
	});
	sim.simulate([&](const SimulatedStep& step) { second.push_back(step.true_pose); });
	ASSERT_EQ(first.size(), second.size());
	for (std::size_t k = 0; k < first.size(); ++k) EXPECT_EQ(first[k], second[k]) << "step " << k;
	EXPECT_EQ(measurements, summary.measurements);
	EXPECT_NEAR(summary.path_length_m, (s.steps - 1) * s.speed_mps * s.dt_s, 1e-9);
	EXPECT_NEAR(summary.meanMeasurementsPerScan(), double(measurements) / s.steps, 1e-12);
}

TEST(Simulator, TrueTurnRateRespectsTheBound)
{
	Scenario s = loadScenario(kSmallIni);
	s.steps = 2000;
	const double max_turn = s.max_turn_rate_deg_s * M_PI / 180 * s.dt_s;
	Pose2 previous;
	Simulator(s).simulate([&](const SimulatedStep& step) {
		if (step.input.index > 0)
		{
			const Pose2 inc = inverseCompose(previous, step.true_pose);
			EXPECT_LE(std::abs(inc.z()), max_turn + 1e-12) << "step " << step.input.index;
			EXPECT_NEAR(inc.head<2>().norm(), s.speed_mps * s.dt_s, 1e-9);
		}
		previous = step.true_pose;
	});
}

#ifdef ESIF_BINARY
TEST(Simulator, CommandWritesRawlogAndGroundTruth)
{
	TempDir dir("command");
	const std::string out = dir.file("cli.rawlog");
	const std::string cmd = std::string(ESIF_BINARY) + " simulate --config " + kSmallIni + " --out " + out +
							" --seed 7 > " + dir.file("stdout.txt");
	ASSERT_EQ(std::system(cmd.c_str()), 0);
	EXPECT_TRUE(fs::exists(out));
	EXPECT_TRUE(fs::exists(dir.file("cli_ground_truth.txt")));
	EXPECT_TRUE(fs::exists(dir.file("cli_ground_truth_robot_path.txt")));
	EXPECT_NE(readBytes(dir.file("stdout.txt")).find("measurements"), std::string::npos);

	Scenario s = loadScenario(kSmallIni);
	s.seed = 7;
	Simulator(s).writeRawlog(dir.file("lib.rawlog"));
	EXPECT_EQ(readBytes(out), readBytes(dir.file("lib.rawlog"))) << "--seed must override [simulation] seed";

	const std::string bad = std::string(ESIF_BINARY) + " simulate --config " + kSmallIni + " --out " + out +
							" --seed -3 2> " + dir.file("stderr.txt");
	EXPECT_NE(std::system(bad.c_str()), 0);
	EXPECT_NE(readBytes(dir.file("stderr.txt")).find("seed"), std::string::npos);
}
#endif
