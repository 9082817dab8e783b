// D-SLAM's guards and its relinearisation:
// - the outlier gates reject corrupted measurements even with landmark IDs,
//   and count them as rejected associations (da_rejected);
// - a diverging map stops the replay at the step it happens with one
//   NumericalError line (exit 3 from the CLI) instead of producing a map;
// - without landmark IDs it survives configs/sim/long_gap.ini, whose 28 m
//   stretches with nothing in view leave the robot metres uncertain in the
//   map frame (the map-level association then leans on tracked features);
// - on grid1225 (book Sec. 3.5) the book's EIF, which never evaluates a map
//   update again, ends overconfident about the map's orientation; evaluating
//   the updates again at the current estimate (relinearise_every_steps) makes
//   the map consistent, as the book reports it;
// - with landmark IDs on long_gap, the noise draws on which it stopped as
//   diverged at the loop closure finish with a consistent map.

#include <EsifTestSupport.h>

#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/eval/Evaluator.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/StatsJson.h>
#include <esif/sim/Scenario.h>
#include <esif/sim/Simulator.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>

namespace
{
using namespace esif;

const std::string kGrid196 = test::sourcePath("rawlogs/grid196.rawlog");

struct Scored
{
	ReplayResult result;
	Accuracy accuracy;
};

Scored run(const Rawlog& log, const std::string& rawlog_path, const std::string& section)
{
	auto plugin = test::makePlugin("Dslam", "association = known_ids\n" + section);
	Scored s;
	s.result = replay(*plugin, log, {0, false});
	s.accuracy = test::scoreAgainstTruth(s.result, groundTruthPrefixFor(rawlog_path));
	return s;
}

/// Adds `offset_m` to the range of every `every`-th measurement from step
/// `from` on, re-observations only when `reobserved_only` (a first sighting
/// is the feature's only evidence, so no gate can judge it); returns how
/// many it corrupted.
std::size_t corruptRanges(Rawlog& log, std::size_t from, std::size_t every, double offset_m,
						  bool reobserved_only = false)
{
	std::size_t n = 0, counted = 0;
	std::set<LandmarkId> seen;
	for (std::size_t k = 0; k < log.steps.size(); ++k)
		if (log.steps[k].scan)
		{
			std::set<LandmarkId> now;
			for (auto& m : log.steps[k].scan->measurements)
			{
				now.insert(*m.id);
				if (k < from || (reobserved_only && !seen.count(*m.id)) || ++counted % every != 0) continue;
				m.range_m += offset_m;
				++n;
			}
			seen.insert(now.begin(), now.end());
		}
	return n;
}

TEST(DslamRobustness, GatesRejectCorruptedMeasurementsWithKnownIds)
{
	const Rawlog clean = readRawlog(kGrid196);
	Rawlog corrupted = clean;
	// 1.5 m is 15 sigma of the range noise: every such measurement fails a
	// 0.999 chi-square gate whatever the (sub-decimetre) map uncertainty.
	// Re-observations only: a corrupted first sighting places its feature
	// wrongly, and the gates then reject its correct measurements instead.
	const std::size_t bad = corruptRanges(corrupted, 100, 50, 1.5, true);
	ASSERT_GT(bad, 250u);  // one measurement in 50 from step 100 on

	const auto reference = run(clean, kGrid196, "");
	const auto gated = run(corrupted, kGrid196, "");
	const auto open = run(corrupted, kGrid196, "outlier_chi2_quantile = 1\nconfirm_new_features = false\n");
	std::cout << "grid196, " << bad << " ranges +1.5 m: rejected " << gated.result.audit.rejectedCount()
			  << " (clean run " << reference.result.audit.rejectedCount() << "); landmark RMSE gated "
			  << *gated.accuracy.landmark_rmse_m << " m, ungated " << *open.accuracy.landmark_rmse_m << " m, clean "
			  << *reference.accuracy.landmark_rmse_m << " m\n";
	// Every corrupted measurement is caught (a few valid ones are rejected too,
	// about 1 in 1000 as the gate's confidence says; the clean run's count).
	EXPECT_GE(gated.result.audit.rejectedCount(), bad);
	EXPECT_LE(gated.result.audit.rejectedCount(), bad + 2 * reference.result.audit.rejectedCount() + 10);
	EXPECT_EQ(open.result.audit.rejectedCount(), 0u);
	// The gated map is about as good as the clean one; without the gate it is
	// not. D-SLAM's RMSE on grid196 is mostly the map's small global rotation
	// fixed while anchoring, one draw per run: measured 0.037 m clean and
	// 0.059 m gated (1.6x), 0.207 m ungated (5.6x). The gated/clean ratio of
	// these two draws moves between 1.2x and 1.6x with how the map updates
	// are linearised (map_linearisation, relinearise_on_correction_m) while
	// 20-draw averages do not move; hence 2x, and 3x for the ungated map.
	EXPECT_LT(*gated.accuracy.landmark_rmse_m, 2.0 * *reference.accuracy.landmark_rmse_m);
	EXPECT_GT(*open.accuracy.landmark_rmse_m, 3.0 * *reference.accuracy.landmark_rmse_m);
	EXPECT_GE(*gated.accuracy.landmark_consistent_fraction, 0.95);
}

TEST(DslamRobustness, DivergenceStopsAtItsStepWithOneLine)
{
	Rawlog log = readRawlog(kGrid196);
	// From step 700 on, the sensor reports every range a kilometre too far:
	// the features first seen then are placed a kilometre away, far beyond
	// twice the path so far plus the sensor range.
	corruptRanges(log, 700, 1, 1000.0);
	// Gates and the second-sighting confirmation off: this test is about the
	// guard's step. (With confirmation on, a feature's two kilometre-off
	// sightings seldom agree while the corrupted re-observations drag the
	// robot, and the map first diverges about 100 steps later.)
	auto plugin = test::makePlugin(
		"Dslam", "association = known_ids\noutlier_chi2_quantile = 1\nconfirm_new_features = false\n");
	try
	{
		replay(*plugin, log, {0, false});
		FAIL() << "a map a kilometre wide was accepted";
	}
	catch (const NumericalError& e)
	{
		const std::string what = e.what();
		std::cout << what << "\n";
		EXPECT_NE(what.find("D-SLAM diverged"), std::string::npos);
		std::smatch step;
		ASSERT_TRUE(std::regex_search(what, step, std::regex("step ([0-9]+): ")));
		// The first features seen from step 700 are placed a kilometre off as
		// soon as they count as mapped: within the next few steps.
		EXPECT_GE(std::stoi(step[1]), 700);
		EXPECT_LE(std::stoi(step[1]), 705);
		EXPECT_EQ(what.find('\n'), std::string::npos) << "one line";
	}
}

/// `config`: relative to the source tree, or absolute.
Stats runCli(const std::string& config, const std::string& rawlog, const std::string& out)
{
	const std::string path = config.front() == '/' ? config : test::sourcePath(config);
	const auto r = test::runEsif("run --quiet --config '" + path + "' --rawlog '" + rawlog +
								 "' --out '" + out + "'");
	EXPECT_EQ(r.exit_code, 0) << config << ": " << r.out;
	if (r.exit_code != 0) return Stats{};
	return Stats::load(out + "/stats.json");
}

TEST(DslamRobustness, WithoutIdsSurvivesLongStretchesWithNothingInView)
{
	// Before the map-level association used the tracked features as
	// anchors, JCBB on this log took a new feature for its mapped grid
	// neighbour after the first crossing, lost the local SLAM's features at
	// the corners, and the run stopped as diverged at step 1312. The first
	// 1400 steps hold both crossings, not the loop closure: closing the loop
	// without IDs is still open (docs/results/consistency.md: JCBB accepts wrong closures on
	// long_gap, and about half the noise draws stop as diverged there).
	test::TempDir dir;
	const std::string log = dir.file("long_gap.rawlog");
	Scenario scenario = test::loadScenario("configs/sim/long_gap.ini");
	scenario.steps = 1400;
	Simulator(scenario).writeRawlog(log);
	const Stats ids = runCli("configs/dslam.ini", log, dir.file("ids"));
	const Stats jcbb = runCli("configs/dslam_jcbb.ini", log, dir.file("jcbb"));
	ASSERT_TRUE(jcbb.number("landmark_rmse_m") && ids.number("landmark_rmse_m"));
	std::cout << "long_gap D-SLAM: landmark RMSE " << test::statNumber(jcbb, "landmark_rmse_m") << " m without IDs, "
			  << test::statNumber(ids, "landmark_rmse_m") << " m with; " << test::statNumber(jcbb, "landmarks")
			  << " vs " << test::statNumber(ids, "landmarks") << " landmarks; " << test::statNumber(jcbb, "da_wrong")
			  << " wrong of " << test::statNumber(jcbb, "da_matched") << " matched\n";
	// Measured: 2.08 m against 2.20 m with IDs (the region mapped after the
	// second crossing is metres off until the loop closes, with IDs or not),
	// 100 % of the landmarks inside their 95 % ellipse, 2 wrong of 3,215
	// matched, 89 features for the 87 seen. The bounds leave room for
	// tuning, not for a failure: a diverged run has no stats, a wrongly
	// associated region is far outside its ellipses.
	EXPECT_LE(test::statNumber(jcbb, "landmark_rmse_m"), 1.5 * test::statNumber(ids, "landmark_rmse_m"));
	EXPECT_GE(test::statNumber(jcbb, "landmark_consistent_fraction"), 0.9);
	EXPECT_LE(test::statNumber(jcbb, "da_wrong"), 0.01 * test::statNumber(jcbb, "da_matched"));
	EXPECT_LE(test::statNumber(jcbb, "landmarks"), 1.15 * test::statNumber(ids, "landmarks"));
}

TEST(DslamRobustness, WithoutIdsHeldFeaturesAnchorLoneSightings)
{
	// configs/sim/lone_sightings.ini: one feature per scan at most, on a 10 m
	// grid. The shipped no-ID config (local_hold_steps = 50) against the same
	// with the book's local SLAM (0), on four noise draws. Measured (eight
	// draws): recall median 0.71 against 0.57, lowest 0.62 against 0.53.
	// The margin, 0.05 on the median, is a third of the measured gain.
	test::TempDir dir;
	std::ifstream shipped_in(test::sourcePath("configs/dslam_jcbb.ini"));
	const std::string shipped((std::istreambuf_iterator<char>(shipped_in)), std::istreambuf_iterator<char>());
	ASSERT_NE(shipped.find("\nlocal_hold_steps = 50\n"), std::string::npos);
	const std::string book_ini = dir.file("book.ini");
	std::ofstream(book_ini) << std::regex_replace(shipped, std::regex("\nlocal_hold_steps = 50\n"),
												  "\nlocal_hold_steps = 0\n");
	std::vector<double> held, book;
	for (int noise_seed = 1; noise_seed <= 4; ++noise_seed)
	{
		Scenario scenario = test::loadScenario("configs/sim/lone_sightings.ini");
		scenario.noise_seed = noise_seed;
		const std::string log = dir.file("lone_" + std::to_string(noise_seed) + ".rawlog");
		Simulator(scenario).writeRawlog(log);
		const std::string tag = std::to_string(noise_seed);
		held.push_back(test::statNumber(runCli("configs/dslam_jcbb.ini", log, dir.file("held" + tag)), "da_recall"));
		book.push_back(test::statNumber(runCli(book_ini, log, dir.file("book" + tag)), "da_recall"));
		std::cout << "lone_sightings noise seed " << noise_seed << ": recall " << held.back() << " held, "
				  << book.back() << " book\n";
	}
	const auto median = [](std::vector<double> v)
	{
		std::sort(v.begin(), v.end());
		return 0.5 * (v[1] + v[2]);
	};
	EXPECT_GE(median(held), median(book) + 0.05);
}

TEST(DslamRobustness, DivergenceExitsWithCodeThreeFromTheCli)
{
	test::TempDir dir;
	// A config whose bound is so tight that the first scan's features exceed
	// it: 0.01 x (0 m of path + 5 m range) = 5 cm.
	std::ofstream(dir.file("tight.ini")) << "[esif]\nplugin = Dslam\n[dslam]\ndivergence_factor = 0.01\n";
	const auto r =
		test::runEsif("run --config " + dir.file("tight.ini") + " --rawlog " + kGrid196 + " --out " + dir.file("out"));
	EXPECT_EQ(r.exit_code, 3) << r.out;
	EXPECT_NE(r.out.find("step 0: D-SLAM diverged"), std::string::npos) << r.out;
	EXPECT_FALSE(std::filesystem::exists(dir.file("out/stats.json")));
}

/// The keys that make D-SLAM the book's: every map update linearised at the
/// estimate of its time and never again, one kidnapped-robot step, no
/// relocalisation.
const std::string kBookDslam =
	"map_linearisation = current\nrelinearise_every_steps = 0\nrelinearise_on_correction_m = 0\n"
	"kidnapped_iterations = 1\nrelocalise_after_disagreeing_scans = 0\n";

/// The defaults before map_linearisation, relinearise_on_correction_m,
/// kidnapped_iterations and relocalise_after_disagreeing_scans: the book's
/// but for the periodic relinearisation.
const std::string kPreviousDefaults =
	"map_linearisation = current\nrelinearise_on_correction_m = 0\nkidnapped_iterations = 1\n"
	"relocalise_after_disagreeing_scans = 0\n";

TEST(DslamRobustness, LongGapLoopClosureKeepsTheMapConsistentWithIds)
{
	// Noise seeds 3, 11 and 12 of a 12-draw campaign on long_gap (three 28 m
	// stretches with nothing in view) stopped as diverged at the loop
	// closure (step ~1800) with the previous defaults: the map updates,
	// linearised at the estimate of their time, had made the region mapped
	// after the gaps 2-4 times over-confident about its orientation, the
	// closing update was linearised where features were metres off, and
	// one kidnapped-robot step from a far start put the robot 8 m off with
	// 0.2 m standard deviation.
	for (const int noise_seed : {3, 11, 12})
	{
		test::TempDir dir;
		Scenario scenario = test::loadScenario("configs/sim/long_gap.ini");
		scenario.noise_seed = noise_seed;
		const std::string path = dir.file("long_gap.rawlog");
		Simulator(scenario).writeRawlog(path);
		const Rawlog log = readRawlog(path);
		Scored shipped;
		ASSERT_NO_THROW(shipped = run(log, path, "")) << "noise seed " << noise_seed;
		std::cout << "long_gap noise seed " << noise_seed << ": landmark RMSE " << *shipped.accuracy.landmark_rmse_m
				  << " m, NEES " << *shipped.accuracy.landmark_nees_mean << ", "
				  << *shipped.accuracy.landmark_consistent_fraction << " inside 95%\n";
		// Measured: 0.38 / 1.15 / 0.57 m, mean NEES 0.95 / 2.43 / 0.78 (2 is
		// the consistent value), 100 / 99.2 / 100% inside. A map that closed
		// the loop wrong is metres off with NEES in the hundreds.
		EXPECT_GE(*shipped.accuracy.landmark_consistent_fraction, 0.9) << "noise seed " << noise_seed;
		EXPECT_LE(*shipped.accuracy.landmark_nees_mean, 4.0) << "noise seed " << noise_seed;
		if (noise_seed == 3)
		{
			EXPECT_THROW(run(log, path, kPreviousDefaults), NumericalError) << "the previous defaults no longer diverge";
		}
	}
}

TEST(DslamRobustness, RelinearisedMapIsConsistentOnGrid1225)
{
	// The first 3000 steps of grid1225 (book Sec. 3.5), 361 features.
	test::TempDir dir;
	Scenario scenario = test::loadScenario("configs/sim/grid1225.ini");
	scenario.steps = 3000;
	const std::string path = dir.file("grid1225_3000.rawlog");
	Simulator(scenario).writeRawlog(path);
	const Rawlog log = readRawlog(path);

	// Both without the second-sighting confirmation, to isolate the
	// relinearisation: with it, the book's EIF is still consistent after
	// these 3000 steps (98%, measured) and falls to 2.0% only over the whole
	// run (1.55 m RMSE against 1.31 m relinearised, 94.7%).
	const auto book = run(log, path, kBookDslam + "confirm_new_features = false\n");
	const auto fixed = run(log, path,
						   "map_linearisation = current\nrelinearise_every_steps = 200\nrelinearise_threshold_m = "
						   "0.01\nconfirm_new_features = false\n");
	std::cout << "grid1225, 3000 steps: book EIF RMSE " << *book.accuracy.landmark_rmse_m << " m, "
			  << *book.accuracy.landmark_consistent_fraction << " consistent, NEES "
			  << *book.accuracy.landmark_nees_mean << "; relinearised " << *fixed.accuracy.landmark_rmse_m << " m, "
			  << *fixed.accuracy.landmark_consistent_fraction << ", NEES " << *fixed.accuracy.landmark_nees_mean
			  << "\n";
	// Measured (seed 1): book 2.0 m, 3% inside the 95% ellipse, NEES 9.5;
	// relinearised 1.4 m, 97.5%, NEES 3.9. The bounds leave room for the
	// platform's rounding, not for the book's EIF to pass.
	EXPECT_LT(*book.accuracy.landmark_consistent_fraction, 0.5);
	EXPECT_GE(*fixed.accuracy.landmark_consistent_fraction, 0.9);
	EXPECT_LT(*fixed.accuracy.landmark_rmse_m, 0.85 * *book.accuracy.landmark_rmse_m);
}

}  // namespace
