/// \file test_SimulatorScenarios.cpp
/// Simulator scenarios for D-SLAM (book Ch. 3): the featureless band (scans
/// that see fewer than two features, Sec. 3.4.1), the scripted waypoint tour,
/// their validation, configs/sim/featureless.ini and configs/sim/grid5000.ini,
/// and the committed grid196 rawlog still reproduced exactly.

#include <EsifTestSupport.h>

#include <esif/config/ConfigFile.h>
#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/formats/GroundTruth.h>
#include <esif/models/Se2.h>
#include <esif/sim/Scenario.h>
#include <esif/sim/Simulator.h>

#include <mrpt/io/CFileGZInputStream.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <vector>

using namespace esif;

namespace
{
Scenario scenarioFromText(const std::string& text)
{
	Scenario s;
	loadParams(s, ConfigFile::fromText("[simulation]\n" + text, "test.ini").section("simulation"));
	return s;
}

/// The ConfigError message of loading `text` and validating it (the
/// Simulator constructor validates); empty when nothing is thrown.
std::string configErrorOf(const std::string& text)
{
	try
	{
		const Scenario s = scenarioFromText(text);
		Simulator{s};
	}
	catch (const ConfigError& e)
	{
		return e.what();
	}
	return {};
}

std::string readBytes(const std::string& path)
{
	std::ifstream in(path, std::ios::binary);
	return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Content of a gz file: compares rawlogs independently of the zlib build.
std::string readGzBytes(const std::string& path)
{
	mrpt::io::CFileGZInputStream in(path);
	std::string out;
	char buf[1 << 16];
	for (std::size_t n; (n = in.Read(buf, sizeof(buf))) > 0;) out.append(buf, n);
	return out;
}

/// A small world with a band and a scripted tour that crosses it twice per
/// round: a 20 m square, 10 x 10 features (2 m spacing), band 7-13 m
/// (removes the columns at x = 7, 9, 11, 13 m).
const char* kBandedTour =
	"world_size_m = 20\nfeatures_per_side = 10\nfeatureless_x_min_m = 7\nfeatureless_x_max_m = 13\n"
	"steps = 1500\nspeed_mps = 1\nmax_turn_rate_deg_s = 30\nstart_x_m = 2\nstart_y_m = 3\nstart_yaw_deg = 0\n"
	"waypoints = 17 3; 17 16; 3 16; 3 5\n";
}  // namespace

TEST(SimulatorScenarios, DefaultsHaveNoBandAndNoScriptAndConfigsAreValid)
{
	const Scenario defaults;
	EXPECT_FALSE(defaults.hasFeaturelessBand());
	EXPECT_TRUE(defaults.scriptedWaypoints().empty());
	EXPECT_EQ(Simulator(defaults).features().size(), 14u * 14u);

	for (const char* name : {"featureless", "grid5000"})
	{
		SCOPED_TRACE(name);
		Scenario s;
		ASSERT_NO_THROW(s = test::loadScenario(std::string("configs/sim/") + name + ".ini"));
		EXPECT_NO_THROW(s.validate());
	}
}

TEST(SimulatorScenarios, Grid5000HasTheDensityOfGrid1225)
{
	const Scenario big = test::loadScenario("configs/sim/grid5000.ini");
	const Scenario book = test::loadScenario("configs/sim/grid1225.ini");
	EXPECT_EQ(Simulator(big).features().size(), 5041u);
	EXPECT_NEAR(big.featureSpacing(), book.featureSpacing(), 1e-6);
	EXPECT_EQ(big.sensor_max_range_m, book.sensor_max_range_m);
	EXPECT_EQ(big.sensor_fov_deg, book.sensor_fov_deg);
	EXPECT_EQ(big.speed_mps, book.speed_mps);
	EXPECT_FALSE(big.hasFeaturelessBand());
	EXPECT_TRUE(big.scriptedWaypoints().empty());
}

/// Features inside the band are gone from the world and the ground truth;
/// the others keep their grid index as ID; no measurement is of a removed
/// feature or of a feature in the band.
TEST(SimulatorScenarios, FeaturesInTheBandAreAbsentFromGroundTruthAndNeverMeasured)
{
	test::TempDir dir;
	const Scenario s = scenarioFromText(kBandedTour);
	ASSERT_TRUE(s.hasFeaturelessBand());
	const Simulator sim(s);
	const int n = s.features_per_side;
	const double spacing = s.featureSpacing();

	// The full grid, for reference: 4 of the 10 columns fall in [7, 13].
	ASSERT_EQ(sim.features().size(), static_cast<std::size_t>(n * (n - 4)));
	ASSERT_EQ(sim.featureIds().size(), sim.features().size());
	EXPECT_TRUE(std::is_sorted(sim.featureIds().begin(), sim.featureIds().end()));
	for (std::size_t i = 0; i < sim.features().size(); ++i)
	{
		const LandmarkId id = sim.featureIds()[i];
		const Eigen::Vector2d& p = sim.features()[i];
		EXPECT_FALSE(s.inFeaturelessBand(p.x())) << "ID " << id;
		// ID = row * n + column, as without the band.
		EXPECT_NEAR(p.x(), (id % n + 0.5) * spacing, 1e-12) << "ID " << id;
		EXPECT_NEAR(p.y(), (id / n + 0.5) * spacing, 1e-12) << "ID " << id;
	}

	const SimulationSummary summary = sim.writeRawlog(dir.file("band.rawlog"));
	const auto truth = loadGroundTruth(groundTruthPrefixFor(dir.file("band.rawlog")));
	ASSERT_TRUE(truth);
	ASSERT_EQ(truth->landmarks.size(), sim.features().size());
	EXPECT_EQ(summary.features, sim.features().size());
	for (std::size_t i = 0; i < sim.features().size(); ++i)
	{
		ASSERT_TRUE(truth->landmarks.count(sim.featureIds()[i])) << "ID " << sim.featureIds()[i];
		EXPECT_NEAR((truth->landmarks.at(sim.featureIds()[i]) - sim.features()[i]).norm(), 0.0, 1e-5);
	}
	for (const auto& [id, p] : truth->landmarks) EXPECT_FALSE(s.inFeaturelessBand(p.x())) << "ID " << id;

	const std::set<LandmarkId> kept(sim.featureIds().begin(), sim.featureIds().end());
	std::set<LandmarkId> measured;
	std::size_t in_band_steps = 0;
	sim.simulate([&](const SimulatedStep& step) {
		for (const auto& m : step.input.scan->measurements)
		{
			ASSERT_TRUE(m.id);
			EXPECT_TRUE(kept.count(*m.id)) << "step " << step.input.index << ": removed feature " << *m.id;
			measured.insert(*m.id);
		}
		if (s.inFeaturelessBand(step.true_pose.x())) ++in_band_steps;
	});
	EXPECT_EQ(measured.size(), summary.features_seen);
	// The tour did cross the band (two 6 m crossings per round).
	EXPECT_GT(in_band_steps, 100u);
	// And saw features on both sides of it.
	const auto side_seen = [&](bool left) {
		return std::any_of(measured.begin(), measured.end(), [&](LandmarkId id) {
			const double x = (id % n + 0.5) * spacing;
			return left ? x < s.featureless_x_min_m : x > s.featureless_x_max_m;
		});
	};
	EXPECT_TRUE(side_seen(true));
	EXPECT_TRUE(side_seen(false));
}

/// The true path passes within reach (1 m) of each scripted waypoint, in the
/// scripted order, and starts the script again after the last one.
TEST(SimulatorScenarios, ScriptedTourVisitsItsWaypointsInOrder)
{
	const Scenario s = scenarioFromText(kBandedTour);
	const std::vector<Eigen::Vector2d> script = s.scriptedWaypoints();
	ASSERT_EQ(script.size(), 4u);
	EXPECT_EQ(script[1], Eigen::Vector2d(17, 16));

	std::vector<Pose2> path;
	Simulator(s).simulate([&](const SimulatedStep& step) { path.push_back(step.true_pose); });

	// Walk the path, waiting for each waypoint in turn.
	const double reach = Scenario::kWaypointReach_m + 1e-9;
	std::size_t visits = 0;
	for (const Pose2& p : path)
		if ((p.head<2>() - script[visits % script.size()]).norm() <= reach) ++visits;
	// The first leg is 15 m, a round 13 + 14 + 11 + (back to the first)
	// 14.1 m = 52 m: 150 m of path make the first leg, two rounds and more.
	EXPECT_GE(visits, 2 * script.size() + 1) << "path length " << (path.size() - 1) * s.speed_mps * s.dt_s << " m";

	// Every waypoint, not only the in-order ones, is passed within reach.
	for (std::size_t i = 0; i < script.size(); ++i)
	{
		double closest = std::numeric_limits<double>::infinity();
		for (const Pose2& p : path) closest = std::min(closest, (p.head<2>() - script[i]).norm());
		EXPECT_LE(closest, reach) << "waypoint " << i + 1;
	}

	// A scripted tour draws no random waypoint: another seed changes the
	// noise, never the true path.
	Scenario other = s;
	other.seed = s.seed + 1;
	std::vector<Pose2> other_path;
	Simulator(other).simulate([&](const SimulatedStep& step) { other_path.push_back(step.true_pose); });
	ASSERT_EQ(other_path.size(), path.size());
	for (std::size_t k = 0; k < path.size(); k += 100) EXPECT_EQ(other_path[k], path[k]) << "step " << k;
}

TEST(SimulatorScenarios, BadBandAndWaypointValuesAreConfigErrorsNamingTheKey)
{
	const auto expectKey = [](const std::string& text, const std::string& key) {
		const std::string error = configErrorOf(text);
		EXPECT_NE(error.find(key), std::string::npos) << "for \"" << text << "\": " << error;
	};
	expectKey("featureless_x_min_m = 20\nfeatureless_x_max_m = 10\n", "featureless_x_min_m");
	expectKey("featureless_x_max_m = wide\n", "featureless_x_max_m");
	expectKey("featureless_x_min_m = 1e400\n", "featureless_x_min_m");

	// Malformed lists (the default world: a 40 m square, start (1, 1)).
	expectKey("waypoints = 10 10; 30\n", "waypoints");
	expectKey("waypoints = 10 10; 30 30 30\n", "waypoints");
	expectKey("waypoints = 10 10;; 30 30\n", "waypoints");
	expectKey("waypoints = 10 10; 30 30;\n", "waypoints");
	expectKey("waypoints = 10 ten; 30 30\n", "waypoints");
	expectKey("waypoints = 10,10; 30,30\n", "waypoints");
	// Rules on the waypoints.
	expectKey("waypoints = 10 10\n", "waypoints");	// a single waypoint
	expectKey("waypoints = 10 10; 30 41\n", "waypoints");	// outside the square
	expectKey("waypoints = 10 10; -1 30\n", "waypoints");
	expectKey("waypoints = 10 10; 30 30; 32 30\n", "waypoints");  // too close to the one before
	expectKey("waypoints = 10 10; 30 30; 12 12\n", "waypoints");  // last too close to the first
	expectKey("waypoints = 2 2; 30 30\n", "waypoints");	 // first too close to the start

	// The message gives the least spacing: 2 speed / turn rate + 2 m.
	const Scenario defaults;
	EXPECT_NEAR(defaults.minWaypointSpacing(), 2 * 1.0 / (30 * M_PI / 180) + 2, 1e-12);
	EXPECT_NE(configErrorOf("waypoints = 10 10; 30 30; 32 30\n").find(formatNumber(defaults.minWaypointSpacing())),
			  std::string::npos);

	// Valid forms: blanks around items, and a waypoint_margin_m that leaves no
	// random waypoint area is irrelevant to a scripted tour.
	EXPECT_EQ(configErrorOf("waypoints =  10 10 ;30 30;  10 30\n"), "");
	EXPECT_EQ(configErrorOf("waypoint_margin_m = 20\nwaypoints = 10 10; 30 30\n"), "");
	EXPECT_NE(configErrorOf("waypoint_margin_m = 20\n").find("waypoint_margin_m"), std::string::npos);
	// Equal ends: no band.
	EXPECT_EQ(configErrorOf("featureless_x_min_m = 5\nfeatureless_x_max_m = 5\n"), "");
	EXPECT_FALSE(scenarioFromText("featureless_x_min_m = 5\nfeatureless_x_max_m = 5\n").hasFeaturelessBand());
}

TEST(SimulatorScenarios, SimulateCommandNamesFileAndKeyOfABadWaypoint)
{
	test::TempDir dir;
	{
		std::ofstream ini(dir.file("bad.ini"));
		ini << "[simulation]\nwaypoints = 10 10; 50 50\n";
	}
	const auto r = test::runEsif("simulate --config " + dir.file("bad.ini") + " --out " + dir.file("x.rawlog"));
	EXPECT_EQ(r.exit_code, 1) << r.out;
	EXPECT_NE(r.out.find("bad.ini"), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("waypoints"), std::string::npos) << r.out;
}

/// configs/sim/featureless.ini: the robot crosses the band 8 times in 2500
/// steps; each crossing is a run of consecutive scans with fewer than two
/// measurements. Measured: 8 runs of 69-74 scans, 526 scans without any
/// measurement, 45 with one. The geometry bounds each run from below: on a
/// straight crossing of the 12 m gap between the columns at x = 9 and 21 m,
/// the 180 deg, 5 m sensor sees nothing from passing x = 9 until x = 16,
/// 7 m = 70 scans at 0.1 m per scan. We ask for 6 runs of >= 60 scans:
/// margin for the heading controller's curves at the ends of the legs, and
/// none for noise, which does not change the true path or what is visible.
TEST(SimulatorScenarios, FeaturelessConfigHasLongRunsOfScansBelowTwoMeasurements)
{
	const Scenario s = test::loadScenario("configs/sim/featureless.ini");
	std::vector<std::size_t> counts;
	std::vector<std::set<LandmarkId>> ids;
	const SimulationSummary summary = Simulator(s).simulate([&](const SimulatedStep& step) {
		counts.push_back(step.input.scan->measurements.size());
		ids.emplace_back();
		for (const auto& m : step.input.scan->measurements) ids.back().insert(*m.id);
	});
	ASSERT_EQ(counts.size(), static_cast<std::size_t>(s.steps));

	std::vector<std::size_t> runs;
	std::size_t run = 0;
	for (std::size_t c : counts)
	{
		if (c < 2) ++run;
		if (c >= 2 && run > 0) runs.push_back(run), run = 0;
	}
	if (run > 0) runs.push_back(run);
	const std::size_t kMinRun = 60;
	const auto long_runs = std::count_if(runs.begin(), runs.end(), [&](std::size_t r) { return r >= kMinRun; });
	EXPECT_GE(long_runs, 6) << "runs of >= " << kMinRun << " scans with < 2 measurements";

	// The summary counts agree.
	EXPECT_EQ(summary.scans_without_measurements, std::size_t(std::count(counts.begin(), counts.end(), 0u)));
	EXPECT_EQ(summary.scans_with_one_measurement, std::size_t(std::count(counts.begin(), counts.end(), 1u)));
	EXPECT_EQ(summary.longest_run_below_two_measurements, *std::max_element(runs.begin(), runs.end()));
	EXPECT_GE(summary.scans_without_measurements, 6 * kMinRun);
	// The long runs are band crossings: after each, the robot sees plenty again.
	EXPECT_GT(summary.meanMeasurementsPerScan(), 4.0);

	// Loop closure: the features of the first scan are measured again after
	// the first round of the tour (about 1250 steps).
	ASSERT_FALSE(ids[0].empty());
	std::set<LandmarkId> seen_again;
	for (std::size_t k = 1000; k < ids.size(); ++k)
		for (LandmarkId id : ids[k])
			if (ids[0].count(id)) seen_again.insert(id);
	EXPECT_EQ(seen_again, ids[0]);
}

/// The scenario options must not change the committed rawlog: configs/sim/
/// grid196.ini still makes rawlogs/grid196.rawlog and its ground truth
/// exactly (rawlog compared uncompressed, so a zlib build cannot matter).
TEST(SimulatorScenarios, Grid196RawlogIsReproducedExactly)
{
	test::TempDir dir;
	const Scenario s = test::loadScenario("configs/sim/grid196.ini");
	Simulator(s).writeRawlog(dir.file("grid196.rawlog"));
	const std::string committed = test::sourcePath("rawlogs/grid196");
	const std::string content = readGzBytes(dir.file("grid196.rawlog"));
	ASSERT_FALSE(content.empty());
	EXPECT_TRUE(content == readGzBytes(committed + ".rawlog")) << "rawlog content differs";
	EXPECT_TRUE(readBytes(dir.file("grid196_ground_truth.txt")) == readBytes(committed + "_ground_truth.txt"));
	EXPECT_TRUE(
		readBytes(dir.file("grid196_ground_truth_robot_path.txt")) ==
		readBytes(committed + "_ground_truth_robot_path.txt"));
}

/// Every committed scenario is within the size caps, and landmarkCount()
/// (what the caps are checked on, before anything is allocated) is the
/// number of features the simulator then places: band and twins included.
TEST(SimulatorScenarios, EveryCommittedScenarioIsWithinTheSizeCapsAndItsLandmarksAreCountedExactly)
{
	std::size_t configs = 0;
	for (const auto& entry : std::filesystem::directory_iterator(test::sourcePath("configs/sim")))
	{
		if (entry.path().extension() != ".ini") continue;
		SCOPED_TRACE(entry.path().string());
		Scenario s;
		ASSERT_NO_THROW(s = Scenario::fromConfig(ConfigFile::load(entry.path().string())));
		EXPECT_NO_THROW(s.validate());
		EXPECT_EQ(s.landmarkCount(), Simulator(s).features().size());
		++configs;
	}
	EXPECT_GE(configs, 12u);
}

/// The measurement estimate of the size check against a simulation: the
/// footprint at the mean density ignores the world's edges, where part of
/// the sensor's sector sees no features, so it may only overestimate, and
/// for a robot kept inside the world (waypoint margin 3 m of 40 m) by a few
/// per cent (grid196: 14,430 estimated, 14,032 simulated); clutter adds its
/// Poisson mean (0.2 a scan, so +-25 in 3000 scans at 1 sigma). Bounds:
/// the estimate within [1, 1 / 0.85] x the simulated count.
TEST(SimulatorScenarios, TheMeasurementEstimateOfTheSizeCheckMatchesASimulation)
{
	for (const char* name : {"grid196", "clutter", "clusters"})
	{
		SCOPED_TRACE(name);
		const Scenario s = test::loadScenario(std::string("configs/sim/") + name + ".ini");
		const SimulationSummary summary = Simulator(s).simulate([](const SimulatedStep&) {});
		const double estimate = s.expectedMeasurementsPerScan() * s.steps;
		EXPECT_GE(estimate, static_cast<double>(summary.measurements));
		EXPECT_GE(static_cast<double>(summary.measurements), 0.85 * estimate);
	}
}

TEST(SimulatorScenarios, SizeCapsAreConfigErrorsNamingTheKeys)
{
	EXPECT_EQ(
		configErrorOf("features_per_side = 1000000\n"),
		"test.ini: [simulation] features_per_side = 1000000: must be in [1, 1000]");
	EXPECT_EQ(configErrorOf("steps = 2000000\n"), "test.ini: [simulation] steps = 2000000: must be in [1, 1e+06]");
	EXPECT_EQ(configErrorOf("dt_s = 3600\n"), "test.ini: [simulation] dt_s = 3600: must be in (0, 60]");
	EXPECT_EQ(
		configErrorOf("std_range_m = 1e300\n"), "test.ini: [simulation] std_range_m = 1e300: must be in [0, 1000]");
	// Within each key's bounds, but 2 x 1000^2 landmarks with the twins.
	EXPECT_EQ(
		configErrorOf("features_per_side = 1000\nworld_size_m = 1000\ncluster_pair_distance_m = 0.1\n"),
		"[simulation] features_per_side = 1000, cluster_pair_distance_m = 0.1: 2000000 landmarks (grid features and "
		"their twins), above the cap of 1000000");
}
