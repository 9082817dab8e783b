// The ID gates of the map-joining filters on grid196 with 1% of the
// measurements given a wrong ID (test::corruptIds, fixed seed): the gate of
// the local-map builder (LandmarkEkf, local_id_gate_chi2_quantile) and the
// map-level gate (id_gate_chi2_quantile) of SLSJF (MapAssociation) and of
// D-SLAM map joining (UpperLevelAssociation), against the clean log and
// against the same filters with both gates off.

#include <EsifTestSupport.h>
#include <WrongIds.h>

#include <esif/eval/Evaluator.h>
#include <esif/formats/GroundTruth.h>

#include <gtest/gtest.h>

#include <map>

namespace
{
using namespace esif;

const std::string kGrid196 = test::sourcePath("rawlogs/grid196.rawlog");

struct JoinedRun
{
	Accuracy accuracy;
	std::size_t wrong = 0, rejected = 0;
	std::map<std::string, double> counters;
};

JoinedRun run(const std::string& plugin_class, const std::string& section, const Rawlog& log)
{
	auto plugin = test::makePlugin(plugin_class, section);
	const ReplayResult r = replay(*plugin, log, {0, false});
	return {test::scoreAgainstTruth(r, groundTruthPrefixFor(kGrid196)), r.audit.wrongCount(), r.audit.rejectedCount(),
			test::countersOf(*plugin)};
}

struct Figures
{
	std::size_t corrupted = 0;
	JoinedRun clean, gated, ungated;
};

/// The filter on clean grid196, on the corrupted copy, and on the corrupted
/// copy with both gates off.
Figures runAll(const std::string& plugin_class, const std::string& section)
{
	const Rawlog clean_log = readRawlog(kGrid196);
	Rawlog corrupted_log = clean_log;
	Figures f;
	f.corrupted = test::corruptIds(corrupted_log, 0.01, 196).size();
	f.clean = run(plugin_class, section, clean_log);
	f.gated = run(plugin_class, section, corrupted_log);
	f.ungated = run(plugin_class, section + "id_gate_chi2_quantile = 1\nlocal_id_gate_chi2_quantile = 1\n", corrupted_log);
	for (const auto& [name, r] : {std::pair{"clean", &f.clean}, {"1% wrong IDs", &f.gated}, {"1% wrong IDs, no gates", &f.ungated}})
		std::cout << plugin_class << ", " << name << ": landmark RMSE " << *r->accuracy.landmark_rmse_m << " m, ATE "
				  << *r->accuracy.ate_rmse_m << " m, da_rejected " << r->rejected << ", da_wrong " << r->wrong
				  << ", map-level ID gate rejections " << r->counters.at("id_gate_rejected") << "\n";
	std::cout << "(" << f.corrupted << " wrong IDs)\n";
	// Clean grid196: nothing for the map-level gate to reject.
	EXPECT_EQ(f.clean.counters.at("id_gate_rejected"), 0);
	EXPECT_EQ(f.clean.wrong, 0u);
	// Without the gates the corrupted log ruins the map (tens of metres).
	EXPECT_GT(*f.ungated.accuracy.landmark_rmse_m, 2 * *f.clean.accuracy.landmark_rmse_m);
	return f;
}

TEST(IdGateMapJoining, SlsjfKeepsItsAccuracyWithWrongIds)
{
	const auto f = runAll("Slsjf", "association = auto\nlocal_map_steps = 45\nlocal_min_range_m = 0.3\n");
	// With the gates, 1% of misreads costs at most 20% of accuracy (the
	// EKF's bound, test_ekf_id_gate): the local gate rejects every misread
	// of a feature confirmed in the local map, the map level the misreads
	// that made a local feature of their own.
	EXPECT_LE(*f.gated.accuracy.landmark_rmse_m, 1.2 * *f.clean.accuracy.landmark_rmse_m);
	EXPECT_LE(*f.gated.accuracy.ate_rmse_m, 1.2 * *f.clean.accuracy.ate_rmse_m);
	EXPECT_GT(f.gated.counters.at("id_gate_rejected"), 0);
}

TEST(IdGateMapJoining, DslamMapJoiningIsOnlyPartlyProtected)
{
	// Known gap: D-SLAM map joining (600-step maps placed through two
	// common features, no odometry between maps) keeps its features
	// (measured 0.058 m landmark RMSE against 0.040 m clean) but not its
	// trajectory: one map fails the map-level gate as a whole (every
	// feature, median squared distance ~4e4 in every reference frame tried),
	// so it and the map after it are unjoinable and their steps keep
	// unplaced poses (17 m ATE against 0.18 m clean; 22 m and 21 m without
	// the gates). Asserted: the gates cut the landmark error at least
	// fivefold, and the trajectory error is the part still open.
	const auto f = runAll("DslamLocalMapJoining",
						  "association = auto\nlocal_map_steps = 600\nlocal_map_min_common_features = 2\n"
						  "local_min_range_m = 0.3\n");
	EXPECT_LT(5 * *f.gated.accuracy.landmark_rmse_m, *f.ungated.accuracy.landmark_rmse_m);
	EXPECT_LE(*f.gated.accuracy.landmark_rmse_m, 2 * *f.clean.accuracy.landmark_rmse_m);
}

}  // namespace
