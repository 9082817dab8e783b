/// \file test_SimulatorOutliers.cpp
/// The simulator's outlier classes and hard layouts: wrong landmark IDs
/// (wrong_id_rate), clutter (spurious_rate), twin landmarks
/// (cluster_pair_distance_m), long stretches without landmarks (a wide
/// featureless band crossed by a scripted tour); the true IDs written beside
/// the rawlog and how the association audit counts against them; and the
/// defaults leaving every output as it was.
///
/// Rates are checked against their distributions: the simulator is
/// deterministic for a seed, so the tolerances say how far a correct
/// implementation may land from the expected value (4 standard deviations:
/// a correct sampler fails with probability below 1e-4 per check, a rate off
/// by a few percent of itself is caught).

#include <EsifTestSupport.h>

#include <esif/config/ConfigFile.h>
#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/eval/AssociationAudit.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/RawlogReader.h>
#include <esif/models/Se2.h>
#include <esif/formats/MeasurementTruth.h>
#include <esif/sim/Scenario.h>
#include <esif/sim/Simulator.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace esif;

namespace
{
/// configs/sim/grid196.ini with `extra` keys added (or overriding).
Scenario grid196With(const std::string& extra)
{
	ConfigFile config = ConfigFile::load(test::sourcePath("configs/sim/grid196.ini"));
	std::istringstream in(extra);
	for (std::string line; std::getline(in, line);)
	{
		const auto eq = line.find('=');
		if (eq == std::string::npos) continue;
		const auto trim = [](std::string t) {
			t.erase(0, t.find_first_not_of(' '));
			t.erase(t.find_last_not_of(' ') + 1);
			return t;
		};
		config.set("simulation", trim(line.substr(0, eq)), trim(line.substr(eq + 1)));
	}
	return Scenario::fromConfig(config);
}

std::vector<SimulatedStep> simulateAll(const Scenario& s, SimulationSummary* summary = nullptr)
{
	std::vector<SimulatedStep> steps;
	const auto sum = Simulator(s).simulate([&](const SimulatedStep& step) { steps.push_back(step); });
	if (summary) *summary = sum;
	return steps;
}

/// The ConfigError message of validating `extra` on grid196; empty when none.
std::string configErrorOf(const std::string& extra)
{
	try
	{
		Simulator{grid196With(extra)};
	}
	catch (const ConfigError& e)
	{
		return e.what();
	}
	return {};
}

/// |count - n p| within 4 binomial standard deviations.
void expectBinomial(std::size_t count, std::size_t n, double p, const std::string& what)
{
	const double mean = n * p, sd = std::sqrt(n * p * (1 - p));
	EXPECT_NEAR(double(count), mean, 4 * sd) << what << ": " << count << " of " << n << " (p = " << p << ")";
}
}  // namespace

TEST(SimulatorOutliers, DefaultsAreOffAndExplicitZerosChangeNothing)
{
	const Scenario defaults;
	EXPECT_EQ(defaults.wrong_id_rate, 0.0);
	EXPECT_EQ(defaults.spurious_rate, 0.0);
	EXPECT_EQ(defaults.cluster_pair_distance_m, 0.0);
	EXPECT_FALSE(defaults.hasOutliers());
	EXPECT_FALSE(defaults.hasClusterPairs());

	// Keys set to their defaults: the same steps, bit for bit.
	Scenario plain = test::loadScenario("configs/sim/small.ini");
	const auto a = simulateAll(plain);
	ConfigFile config = ConfigFile::load(test::sourcePath("configs/sim/small.ini"));
	config.set("simulation", "wrong_id_rate", "0");
	config.set("simulation", "spurious_rate", "0");
	config.set("simulation", "cluster_pair_distance_m", "0");
	const auto b = simulateAll(Scenario::fromConfig(config));
	ASSERT_EQ(a.size(), b.size());
	for (std::size_t k = 0; k < a.size(); ++k)
	{
		const auto& ma = a[k].input.scan->measurements;
		const auto& mb = b[k].input.scan->measurements;
		ASSERT_EQ(ma.size(), mb.size()) << "step " << k;
		for (std::size_t i = 0; i < ma.size(); ++i)
		{
			EXPECT_EQ(ma[i].range_m, mb[i].range_m);
			EXPECT_EQ(ma[i].bearing_rad, mb[i].bearing_rad);
			EXPECT_EQ(ma[i].id, mb[i].id);
			EXPECT_EQ(a[k].true_ids[i], ma[i].id) << "without outliers the rawlog's ID is the truth";
		}
	}

	// No measurement-truth file without outliers: the output set is as before.
	test::TempDir dir;
	Simulator(plain).writeRawlog(dir.file("small.rawlog"));
	EXPECT_FALSE(std::filesystem::exists(measurementTruthFileOf(dir.file("small"))));
	EXPECT_FALSE(loadMeasurementTruth(dir.file("small"), 10).has_value());
}

TEST(SimulatorOutliers, BadValuesAreConfigErrorsNamingTheKey)
{
	EXPECT_NE(configErrorOf("wrong_id_rate = 1.5").find("wrong_id_rate"), std::string::npos);
	EXPECT_NE(configErrorOf("wrong_id_rate = -0.1").find("wrong_id_rate"), std::string::npos);
	EXPECT_NE(configErrorOf("spurious_rate = -1").find("spurious_rate"), std::string::npos);
	EXPECT_NE(configErrorOf("spurious_rate = 1000").find("spurious_rate"), std::string::npos);
	EXPECT_NE(configErrorOf("cluster_pair_distance_m = -0.2").find("cluster_pair_distance_m"), std::string::npos);
	// grid196's spacing is 40 / 14 = 2.857 m: a twin 1.5 m away could be
	// 1.36 m from a neighbouring grid feature, nearer than to its own.
	const std::string far = configErrorOf("cluster_pair_distance_m = 1.5");
	EXPECT_NE(far.find("[simulation] cluster_pair_distance_m = 1.5: must be less than half the feature spacing"),
			  std::string::npos)
		<< far;
	EXPECT_EQ(configErrorOf("cluster_pair_distance_m = 1.4"), "");
	EXPECT_EQ(configErrorOf("wrong_id_rate = 1\nspurious_rate = 100"), "");
}

/// Misreads change IDs only, at the configured rate, to one of the 8
/// landmarks nearest to the true one that the scan does not hold; the path,
/// noise and true measurements stay those of grid196.
TEST(SimulatorOutliers, WrongIdsAtTheirRateAmongTheNearestLandmarks)
{
	SimulationSummary clean_summary, summary;
	const Scenario clean_scenario = test::loadScenario("configs/sim/grid196.ini");
	const auto clean = simulateAll(clean_scenario, &clean_summary);
	const double rate = 0.05;  // high enough that the relative tolerance is tight (+-9 %)
	const auto noisy = simulateAll(grid196With("wrong_id_rate = " + std::to_string(rate)), &summary);
	ASSERT_EQ(clean.size(), noisy.size());
	const Simulator sim(clean_scenario);
	std::map<LandmarkId, Eigen::Vector2d> position;
	for (std::size_t j = 0; j < sim.features().size(); ++j) position[sim.featureIds()[j]] = sim.features()[j];

	std::size_t corrupted = 0;
	for (std::size_t k = 0; k < clean.size(); ++k)
	{
		const auto& mc = clean[k].input.scan->measurements;
		const auto& mn = noisy[k].input.scan->measurements;
		ASSERT_EQ(mc.size(), mn.size()) << "step " << k;
		std::set<LandmarkId> in_scan, rawlog_ids;
		for (const auto& m : mc) in_scan.insert(*m.id);
		for (const auto& m : mn) rawlog_ids.insert(*m.id);
		EXPECT_EQ(rawlog_ids.size(), mn.size()) << "one ID at most once per scan (MRPT's rule), step " << k;
		for (std::size_t i = 0; i < mc.size(); ++i)
		{
			ASSERT_EQ(mc[i].range_m, mn[i].range_m);
			ASSERT_EQ(mc[i].bearing_rad, mn[i].bearing_rad);
			ASSERT_EQ(noisy[k].true_ids[i], mc[i].id) << "true IDs are the clean run's";
			const LandmarkId truth = *mc[i].id, given = *mn[i].id;
			if (given == truth) continue;
			++corrupted;
			EXPECT_EQ(in_scan.count(given), 0u) << "a misread names a landmark the scan does not measure";
			// Fewer than 8 landmarks outside the scan are nearer to the true one.
			const double d = (position.at(given) - position.at(truth)).norm();
			std::size_t nearer = 0;
			for (const auto& [id, p] : position)
				if (id != truth && !in_scan.count(id) && (p - position.at(truth)).norm() < d - 1e-9) ++nearer;
			EXPECT_LT(nearer, 8u) << "step " << k << ": " << truth << " read as " << given;
		}
	}
	EXPECT_EQ(corrupted, summary.wrong_id_measurements);
	EXPECT_EQ(summary.measurements, clean_summary.measurements);
	expectBinomial(corrupted, summary.measurements, rate, "misread measurements");
}

TEST(SimulatorOutliers, WrongIdsConfigHasOnePercent)
{
	SimulationSummary summary;
	const Scenario s = test::loadScenario("configs/sim/wrong_ids.ini");
	EXPECT_EQ(s.wrong_id_rate, 0.01);
	simulateAll(s, &summary);
	expectBinomial(summary.wrong_id_measurements, summary.measurements, 0.01, "wrong_ids.ini");
}

/// Clutter: a Poisson number per scan, uniform over the sensed area, fresh
/// IDs above every landmark's; the true measurements are untouched.
TEST(SimulatorOutliers, ClutterIsPoissonUniformInTheSensedAreaWithFreshIds)
{
	SimulationSummary summary;
	const double rate = 0.5;
	const Scenario s = grid196With("spurious_rate = 0.5");
	const auto clean = simulateAll(test::loadScenario("configs/sim/grid196.ini"));
	const auto noisy = simulateAll(s, &summary);
	ASSERT_EQ(clean.size(), noisy.size());
	const double half_fov = s.sensor_fov_deg * M_PI / 360;

	std::size_t clutter = 0, scans_without_clutter = 0, inner = 0, left = 0;
	std::set<LandmarkId> clutter_ids;
	for (std::size_t k = 0; k < noisy.size(); ++k)
	{
		const auto& mn = noisy[k].input.scan->measurements;
		ASSERT_EQ(noisy[k].true_ids.size(), mn.size());
		std::vector<RangeBearing> true_ones;
		std::size_t here = 0;
		for (std::size_t i = 0; i < mn.size(); ++i)
		{
			if (noisy[k].true_ids[i])
			{
				true_ones.push_back(mn[i]);
				continue;
			}
			++here;
			EXPECT_GE(*mn[i].id, s.clutterIdBase());
			EXPECT_TRUE(clutter_ids.insert(*mn[i].id).second) << "clutter IDs are unique";
			EXPECT_LE(mn[i].range_m, s.sensor_max_range_m);
			EXPECT_LE(std::abs(mn[i].bearing_rad), half_fov);
			if (mn[i].range_m < s.sensor_max_range_m / std::sqrt(2.0)) ++inner;
			if (mn[i].bearing_rad > 0) ++left;
		}
		clutter += here;
		if (here == 0) ++scans_without_clutter;
		// Without the clutter, the scan is grid196's.
		const auto& mc = clean[k].input.scan->measurements;
		ASSERT_EQ(true_ones.size(), mc.size()) << "step " << k;
		for (std::size_t i = 0; i < mc.size(); ++i)
		{
			EXPECT_EQ(true_ones[i].range_m, mc[i].range_m);
			EXPECT_EQ(true_ones[i].id, mc[i].id);
		}
	}
	EXPECT_EQ(clutter, summary.spurious_measurements);
	const double n = double(noisy.size());
	// Total over 3000 scans: Poisson(rate n), standard deviation sqrt(rate n).
	EXPECT_NEAR(double(clutter), rate * n, 4 * std::sqrt(rate * n));
	// Scans without clutter: binomial with P(0) = exp(-rate), which a
	// non-Poisson count of the same mean (e.g. always 0 or 1) misses.
	expectBinomial(scans_without_clutter, noisy.size(), std::exp(-rate), "scans without clutter");
	// Uniform over the area: half of it lies within R / sqrt(2); half of the
	// field of view to the left.
	expectBinomial(inner, clutter, 0.5, "clutter within R / sqrt(2)");
	expectBinomial(left, clutter, 0.5, "clutter to the left");
	// Fresh IDs: none of a landmark.
	const Simulator sim(s);
	for (const LandmarkId id : sim.featureIds()) EXPECT_EQ(clutter_ids.count(id), 0u);
}

/// Twins: each grid feature's exactly at the configured distance, in a
/// uniformly random direction, with its own ID; both measured.
TEST(SimulatorOutliers, ClusterPairsAreExactlyTheirDistanceApart)
{
	const Scenario s = test::loadScenario("configs/sim/clusters.ini");
	EXPECT_EQ(s.cluster_pair_distance_m, 0.2);
	const Simulator sim(s);
	const std::size_t grid = 196;
	ASSERT_EQ(sim.features().size(), 2 * grid);
	std::map<int, std::size_t> quadrants;
	for (std::size_t i = 0; i < grid; ++i)
	{
		const Eigen::Vector2d d = sim.features()[grid + i] - sim.features()[i];
		EXPECT_NEAR(d.norm(), 0.2, 1e-12);
		EXPECT_EQ(sim.featureIds()[grid + i], sim.featureIds()[i] + LandmarkId(grid));
		++quadrants[(d.x() > 0 ? 0 : 1) + (d.y() > 0 ? 0 : 2)];
		// The nearest other feature of each grid feature is its twin.
		double nearest = INFINITY;
		std::size_t nearest_index = 0;
		for (std::size_t j = 0; j < sim.features().size(); ++j)
			if (j != i && (sim.features()[j] - sim.features()[i]).norm() < nearest)
				nearest = (sim.features()[j] - sim.features()[i]).norm(), nearest_index = j;
		EXPECT_EQ(nearest_index, grid + i);
	}
	EXPECT_TRUE(std::is_sorted(sim.featureIds().begin(), sim.featureIds().end()));
	for (int q = 0; q < 4; ++q) expectBinomial(quadrants[q], grid, 0.25, "twin directions in quadrant");

	// The ground truth lists both of each pair; both are measured.
	SimulationSummary summary;
	simulateAll(s, &summary);
	EXPECT_GT(summary.features_seen, 2 * 150u) << "grid196's path sees 164 of 196 grid features";
	test::TempDir dir;
	sim.writeRawlog(dir.file("clusters.rawlog"));
	const auto truth = loadGroundTruth(dir.file("clusters"));
	ASSERT_TRUE(truth);
	EXPECT_EQ(truth->landmarks.size(), 2 * grid);
	EXPECT_NEAR((truth->landmarks.at(200) - truth->landmarks.at(4)).norm(), 0.2, 1e-5);	 // file keeps 6 decimals
}

/// configs/sim/long_gap.ini: along each band crossing the robot has no
/// landmark in view for about 28 m, checked against the geometry.
TEST(SimulatorOutliers, LongGapConfigDrivesLongStretchesWithNothingInView)
{
	const Scenario s = test::loadScenario("configs/sim/long_gap.ini");
	SimulationSummary summary;
	const auto steps = simulateAll(s, &summary);
	const Simulator sim(s);
	for (const auto& p : sim.features()) EXPECT_FALSE(p.x() > 15 && p.x() < 45) << p.transpose();

	// Between the last column the sensor can see behind it (x = 13.5 m,
	// leaving the 180 deg field of view once passed) and the first within
	// its 5 m range ahead (x = 46.5 m: from x = 41.5 m), nothing is in
	// view, in either direction: checked on every scan whose true position
	// is at 19 < x < 41 m, away from where the view opens in either direction.
	std::size_t in_gap = 0, eastward = 0, westward = 0;
	for (const auto& step : steps)
	{
		const double x = step.true_pose.x();
		if (x <= 19 || x >= 41) continue;
		++in_gap;
		EXPECT_TRUE(step.input.scan->measurements.empty()) << "step " << step.input.index << " at x = " << x;
		(std::cos(step.true_pose.z()) > 0 ? eastward : westward)++;
	}
	// Three crossings of 22 m each at 0.1 m per scan, less the legs' slight
	// deviation from straight lines.
	EXPECT_GT(eastward, 2 * 200u);
	EXPECT_GT(westward, 200u);
	EXPECT_EQ(in_gap, eastward + westward);
	// The longest run of empty scans is a whole crossing: 33 m between the
	// columns less the 5 m of range ahead = 28 m, i.e. about 280 scans.
	EXPECT_GE(summary.longest_run_without_measurements, 270u);
	EXPECT_LE(summary.longest_run_without_measurements, 290u);
	// The tour returns over the start: the first scan's features are seen
	// again at the end.
	std::set<LandmarkId> first;
	for (const auto& m : steps.front().input.scan->measurements) first.insert(*m.id);
	ASSERT_FALSE(first.empty());
	std::set<LandmarkId> again;
	for (std::size_t k = 1800; k < steps.size(); ++k)
		for (const auto& m : steps[k].input.scan->measurements)
			if (first.count(*m.id)) again.insert(*m.id);
	EXPECT_EQ(again, first);
}

/// The rawlog written with outliers, read back: its IDs are the corrupted
/// ones, the measurement-truth file has the true ones; the association
/// audit counts against whichever it is given.
TEST(SimulatorOutliers, MeasurementTruthFileAndTheAuditThatUsesIt)
{
	test::TempDir dir;
	const Scenario s = grid196With("wrong_id_rate = 0.02\nspurious_rate = 0.1");
	const Simulator sim(s);
	const SimulationSummary summary = sim.writeRawlog(dir.file("out.rawlog"));
	const Rawlog log = readRawlog(dir.file("out.rawlog"));
	const auto truth = loadMeasurementTruth(dir.file("out"), log.true_ids.size());
	ASSERT_TRUE(truth);
	ASSERT_EQ(truth->size(), log.true_ids.size());

	std::size_t differing = 0, clutter = 0;
	for (std::size_t k = 0; k < log.true_ids.size(); ++k)
	{
		ASSERT_EQ((*truth)[k].size(), log.true_ids[k].size()) << "step " << k;
		for (std::size_t i = 0; i < log.true_ids[k].size(); ++i)
		{
			if (!(*truth)[k][i])
				++clutter;
			else if ((*truth)[k][i] != log.true_ids[k][i])
				++differing;
		}
	}
	EXPECT_EQ(differing, summary.wrong_id_measurements);
	EXPECT_EQ(clutter, summary.spurious_measurements);
	EXPECT_GT(differing, 0u);
	EXPECT_GT(clutter, 0u);

	// A filter that trusts the IDs (landmark = rawlog ID) and one that
	// associates perfectly (landmark = true landmark; clutter rejected).
	AssociationAudit trusting_vs_rawlog, trusting_vs_truth, perfect_vs_rawlog, perfect_vs_truth;
	for (std::size_t k = 0; k < log.true_ids.size(); ++k)
	{
		StepReport trusting, perfect;
		std::set<LandmarkId> trusted_seen, perfect_seen;
		for (std::size_t i = 0; i < log.true_ids[k].size(); ++i)
		{
			const LandmarkId rawlog_id = *log.true_ids[k][i];
			trusting.associations.push_back({Association::Kind::Matched, rawlog_id});
			const auto true_id = (*truth)[k][i];
			perfect.associations.push_back(
				true_id ? Association{Association::Kind::Matched, *true_id} : Association{Association::Kind::Rejected, -1});
		}
		trusting_vs_rawlog.record(trusting, log.true_ids[k]);
		trusting_vs_truth.record(trusting, (*truth)[k]);
		perfect_vs_rawlog.record(perfect, log.true_ids[k]);
		perfect_vs_truth.record(perfect, (*truth)[k]);
	}
	// Against the rawlog's IDs the trusting filter looks perfect and the
	// perfect one wrong once per misread; against the truth, the reverse.
	EXPECT_EQ(trusting_vs_rawlog.wrongCount(), 0u);
	EXPECT_EQ(perfect_vs_truth.wrongCount(), 0u);
	// Each misread is one wrong measurement (or, when its wrong landmark has
	// no other measurement, one true landmark split over two filter
	// landmarks): the count equals the misreads. Clutter carries no truth
	// and is not scored.
	EXPECT_EQ(trusting_vs_truth.wrongCount(), summary.wrong_id_measurements);
	EXPECT_EQ(perfect_vs_rawlog.wrongCount(), summary.wrong_id_measurements);
}

TEST(SimulatorOutliers, MeasurementTruthFileErrorsNameFileAndLine)
{
	test::TempDir dir;
	std::ofstream(dir.file("bad_ground_truth_measurement_ids.txt")) << "% header\n0 0 5 5\n0 2 6 6\n";
	try
	{
		loadMeasurementTruth(dir.file("bad"), 10);
		FAIL() << "rows out of order must be an error";
	}
	catch (const InputError& e)
	{
		EXPECT_NE(std::string(e.what()).find("bad_ground_truth_measurement_ids.txt:3: "), std::string::npos)
			<< e.what();
	}
	std::ofstream(dir.file("worse_ground_truth_measurement_ids.txt")) << "0 0 five 5\n";
	EXPECT_THROW(loadMeasurementTruth(dir.file("worse"), 10), InputError);

	// Round trip, with a step without measurements and clutter.
	MeasurementTruth t = {{{3, 3}, {9, std::nullopt}}, {}, {{4, 7}}};
	saveMeasurementTruth(t, dir.file("ok"));
	const auto back = loadMeasurementTruth(dir.file("ok"), 3);
	ASSERT_TRUE(back);
	const std::vector<std::vector<std::optional<LandmarkId>>> expected = {{3, std::nullopt}, {}, {7}};
	EXPECT_EQ(*back, expected);
}

/// A 16-byte file naming step 10^9 is refused at its line before anything
/// is allocated for the steps it implies (it used to allocate 24 GB and end
/// in std::bad_alloc): steps are bounded by the rawlog's.
TEST(SimulatorOutliers, MeasurementTruthStepsAreBoundedByTheRawlogs)
{
	test::TempDir dir;
	std::ofstream(dir.file("huge_ground_truth_measurement_ids.txt")) << "1000000000 0 5 5\n";
	try
	{
		loadMeasurementTruth(dir.file("huge"), 3000);
		FAIL() << "a step beyond the rawlog's must be an error";
	}
	catch (const InputError& e)
	{
		EXPECT_NE(std::string(e.what()).find("huge_ground_truth_measurement_ids.txt:1: step 1000000000 but the rawlog has 3000 steps"),
				  std::string::npos)
			<< e.what();
	}
	std::ofstream(dir.file("id_ground_truth_measurement_ids.txt")) << "0 0 5 4294967296\n";
	EXPECT_THROW(loadMeasurementTruth(dir.file("id"), 10), InputError) << "a true ID beyond int32";
	std::filesystem::create_directory(dir.file("folder_ground_truth_measurement_ids.txt"));
	EXPECT_THROW(loadMeasurementTruth(dir.file("folder"), 10), InputError) << "a folder where the file belongs";
}
