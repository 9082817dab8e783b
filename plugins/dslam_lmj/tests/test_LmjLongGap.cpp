// D-SLAM map joining with landmark IDs on configs/sim/long_gap.ini (three
// 28 m stretches with no landmark in view) with maps closed at the step
// limit whether or not they hold two features of the previous map
// (local_map_min_common_features = 0). A map that starts in a featureless
// stretch then shares no feature with the global map and is joined with the
// map fused before it through their shared pose (Sec. 4.4.4 fallback): that
// fusion is withdrawn and the joined map fused anew. The features the
// withdrawn fusion created have no other information; when the ID gate
// rejected one of them in the joined map, it was left in the global map with
// no information at all and the next recovery failed ("the information
// matrix is singular"): noise seeds 5 (200-step maps) and 12 (100-step
// maps) of a 12-seed Monte Carlo campaign.
//
// Second issue: each map's update (eq. 4.17) is linearised once, at the
// estimate before its fusion. Maps fused after a crossing, before the loop
// closes, are linearised metres away from where the closure puts their
// features, and the map ends biased and over-confident; relinearise_after_fusion
// re-evaluates the updates at the current estimate after each fusion.
// Each log is simulated here (0.5 s).

#include <EsifTestSupport.h>

#include <esif/config/ConfigFile.h>
#include <esif/eval/Evaluator.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/RawlogReader.h>
#include <esif/sim/Scenario.h>
#include <esif/sim/Simulator.h>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <map>

namespace
{
using namespace esif;

struct LmjRun
{
	Accuracy accuracy;
	std::map<std::string, double> counters;
	std::vector<LandmarkEstimate> landmarks;
};

/// configs/dslam_lmj.ini with known IDs, maps of `steps` steps closed
/// without waiting for common features, on long_gap with `noise_seed`;
/// `extra` keys appended.
LmjRun runLongGap(int noise_seed, int steps, const std::string& extra = "")
{
	test::TempDir dir;
	auto scenario = test::loadScenario("configs/sim/long_gap.ini");
	scenario.noise_seed = noise_seed;
	Simulator(scenario).writeRawlog(dir.file("long_gap.rawlog"));
	const Rawlog log = readRawlog(dir.file("long_gap.rawlog"));
	auto lmj = test::makePlugin(
		"DslamLocalMapJoining",
		"association = known_ids\nlocal_map_steps = " + std::to_string(steps) +
			"\nlocal_map_min_common_features = 0\nlocal_min_range_m = 0.3\nlocal_id_gate_chi2_quantile = 0.9999\n"
			"local_update_iterations = 10\nlocal_relinearise_above_d2 = 1\nid_gate_chi2_quantile = 0.9999\n" + extra);
	const auto result = replay(*lmj, log, {0, false});
	return {test::scoreAgainstTruth(result, dir.file("long_gap")), test::countersOf(*lmj),
			result.record.final_estimate.landmarks};
}

void expectJoinedAndInformed(int noise_seed, int steps)
{
	LmjRun run;
	ASSERT_NO_THROW(run = runLongGap(noise_seed, steps)) << "noise seed " << noise_seed << ", " << steps << "-step maps";
	std::cout << "long_gap noise seed " << noise_seed << ", " << steps << "-step maps: "
			  << run.counters.at("local_maps_merged") << " maps joined, landmark RMSE " << *run.accuracy.landmark_rmse_m
			  << " m, " << *run.accuracy.landmark_consistent_fraction << " inside 95%\n";
	// The join path ran (maps starting in a featureless stretch).
	EXPECT_GE(run.counters.at("local_maps_merged"), 1);
	// Every feature of the global map is informed: a positive-definite covariance.
	for (const auto& l : run.landmarks)
	{
		EXPECT_TRUE(l.cov.allFinite()) << "feature " << l.id;
		EXPECT_GT(l.cov.determinant(), 0) << "feature " << l.id;
	}
	// Accuracy of this setting over the 12-seed campaign (esif montecarlo,
	// seeds 1..12, 200-step maps): 0.86 +- 0.39 m; the bound is that mean
	// plus about three standard deviations (measured here: seed 5 0.90 m,
	// seed 12 0.20 m).
	EXPECT_LT(*run.accuracy.landmark_rmse_m, 2.0);
}

TEST(LmjLongGap, AJoinKeepsTheFeaturesOfTheWithdrawnFusionInformed200StepMaps) { expectJoinedAndInformed(5, 200); }

TEST(LmjLongGap, AJoinKeepsTheFeaturesOfTheWithdrawnFusionInformed100StepMaps) { expectJoinedAndInformed(12, 100); }

TEST(LmjLongGap, RelinearisingTheGlobalMapAfterEachFusionKeepsItConsistent)
{
	// Noise seed 2 of the campaign, where the single linearisation is far off.
	const LmjRun once = runLongGap(2, 200);
	const LmjRun relinearised = runLongGap(2, 200, "relinearise_after_fusion = true\nrelinearise_iterations = 5\n");
	std::cout << "long_gap noise seed 2, 200-step maps: linearised once: landmark RMSE " << *once.accuracy.landmark_rmse_m
			  << " m, " << *once.accuracy.landmark_consistent_fraction << " inside 95%, NEES "
			  << *once.accuracy.landmark_nees_mean << "; relinearised (" << relinearised.counters.at("relinearised_terms")
			  << " terms): " << *relinearised.accuracy.landmark_rmse_m << " m, "
			  << *relinearised.accuracy.landmark_consistent_fraction << " inside 95%, NEES "
			  << *relinearised.accuracy.landmark_nees_mean << "\n";
	// Measured: once 1.29 m, 19.5% inside, NEES 35.5; relinearised 0.29 m,
	// 100% inside, NEES 1.29. Over the 12-seed campaign relinearised: RMSE
	// 0.55 +- 0.39 m, landmark ANEES 2.17 (95% bounds 1.03-3.28), 92% of the
	// landmarks inside; once: 0.86 +- 0.37 m, ANEES 17.6.
	EXPECT_GT(relinearised.counters.at("relinearised_terms"), 0);
	// A consistent filter: mean NEES of 2 dof about 2 (bound: the campaign's
	// upper 95% bound), about 95% inside (bound 90%).
	EXPECT_LT(*relinearised.accuracy.landmark_nees_mean, 3.3);
	EXPECT_GE(*relinearised.accuracy.landmark_consistent_fraction, 0.9);
	// The campaign's mean RMSE plus a margin for one draw.
	EXPECT_LT(*relinearised.accuracy.landmark_rmse_m, 0.6);
	// The book's single linearisation on the same draw: the over-confidence fixed here.
	EXPECT_GT(*once.accuracy.landmark_nees_mean, 3 * *relinearised.accuracy.landmark_nees_mean);
}

}  // namespace
