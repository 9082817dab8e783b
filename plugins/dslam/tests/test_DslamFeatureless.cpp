// D-SLAM across featureless stretches (book Sec. 3.4.1, admissible
// measurements): configs/sim/featureless.ini crosses a 12 m gap between
// feature columns 8 times, each a run of ~70 scans that see fewer than two
// features. Combining those scans into virtual observations must keep
// mapping going on the far side; skipping them must not.

#include <ConsistencyCampaign.h>
#include <EsifTestSupport.h>

#include <esif/config/ConfigFile.h>
#include <esif/eval/Evaluator.h>
#include <esif/formats/GroundTruth.h>
#include <esif/sim/Simulator.h>

#include <gtest/gtest.h>

#include <algorithm>

namespace
{
using namespace esif;
using test::pluginCounter;

struct Scored
{
	FilterPlugin::Ptr plugin;
	ReplayResult result;
	Accuracy accuracy;
};

class DslamFeatureless : public ::testing::Test
{
   protected:
	static void SetUpTestSuite()
	{
		dir_ = new test::TempDir;
		Scenario scenario;
		loadParams(scenario, ConfigFile::load(test::sourcePath("configs/sim/featureless.ini")).section("simulation"));
		Simulator(scenario).writeRawlog(dir_->file("featureless.rawlog"));
	}
	static void TearDownTestSuite() { delete dir_; }

	static Scored run(const std::string& plugin_class, const std::string& section)
	{
		const std::string path = dir_->file("featureless.rawlog");
		const Rawlog log = readRawlog(path);
		Scored s{test::makePlugin(plugin_class, section), {}, {}};
		s.result = replay(*s.plugin, log, {0, false});
		s.accuracy = test::scoreAgainstTruth(s.result, groundTruthPrefixFor(path));
		return s;
	}

	static test::TempDir* dir_;
};
test::TempDir* DslamFeatureless::dir_ = nullptr;

TEST_F(DslamFeatureless, VirtualObservationsKeepMappingAcrossTheGap)
{
	const auto ekf = run("EkfSlam", "association = known_ids\n");
	const auto combine = run("Dslam", "association = known_ids\n");
	const auto skip = run("Dslam", "association = known_ids\nadmissible = skip\n");
	const auto& p = *combine.plugin;
	std::cout << "featureless: landmarks EKF " << ekf.result.record.final_estimate.landmarks.size() << ", D-SLAM "
			  << combine.result.record.final_estimate.landmarks.size() << " (skip: "
			  << skip.result.record.final_estimate.landmarks.size() << "); RMSE EKF " << *ekf.accuracy.landmark_rmse_m
			  << " m, D-SLAM " << *combine.accuracy.landmark_rmse_m << " m; inadmissible scans "
			  << pluginCounter(p, "inadmissible_scans") << ", withdrawals " << pluginCounter(p, "map_withdrawals")
			  << ", virtual updates " << pluginCounter(p, "virtual_updates") << "\n";

	// Every feature the EKF maps, D-SLAM maps: the far side of each gap is
	// reached through virtual observations ...
	EXPECT_EQ(combine.result.record.final_estimate.landmarks.size(), ekf.result.record.final_estimate.landmarks.size());
	EXPECT_EQ(combine.result.audit.wrongCount(), 0u);
	// ... which happened: each inadmissible scan after the anchor withdrew
	// the previous update and replaced it.
	EXPECT_GT(pluginCounter(p, "virtual_updates"), 8);  // at least once per crossing
	EXPECT_EQ(pluginCounter(p, "map_withdrawals"), pluginCounter(p, "inadmissible_scans") - 1);
	// Skipping those scans loses the far side of the first gap for good.
	EXPECT_LT(skip.result.record.final_estimate.landmarks.size(),
			  combine.result.record.final_estimate.landmarks.size() * 2 / 3);
	// Accuracy: both filters pay for the heading drift across the gaps (a
	// few degrees of map rotation); D-SLAM no more than half again the EKF.
	EXPECT_LE(*combine.accuracy.landmark_rmse_m, 1.5 * *ekf.accuracy.landmark_rmse_m);
}

TEST_F(DslamFeatureless, AccurateAndLandmarksConsistentFromBothSidesAcrossTheGaps)
{
	const auto dslam = run("Dslam", "association = known_ids\n");
	const auto& a = dslam.accuracy;
	ASSERT_TRUE(a.landmark_rmse_m && a.ate_rmse_m && a.landmark_nees_mean && a.pose_nees_mean);
	std::cout << "featureless D-SLAM: landmark RMSE " << *a.landmark_rmse_m << " m, ATE " << *a.ate_rmse_m
			  << " m, landmark NEES mean " << *a.landmark_nees_mean << ", pose NEES mean " << *a.pose_nees_mean
			  << ", landmarks consistent " << *a.landmark_consistent_fraction << "\n";
	// Absolute accuracy (measured: landmarks 0.18 m, trajectory 1.40 m; the
	// EKF's map 1.23 m). Each of the 8 crossings is ~70 scans of dead
	// reckoning at 3 deg/s turn-rate noise, a few degrees of heading and
	// decimetres to a metre of position by the far side, which the first
	// scans there correct in the map but not in the path already driven.
	// The full-SLAM baseline is no reference here: from dead reckoning it
	// stops in a local minimum on this rawlog (chi2/dof 7.1, flagged
	// implausible; landmark RMSE 1.42 m). Bounds: 40 % above the measurements.
	EXPECT_LT(*a.landmark_rmse_m, 0.25);
	EXPECT_LT(*a.ate_rmse_m, 2.0);
	// Landmark consistency, both sides. One run's landmark NEES mean is in
	// the worst case (errors shared through the crossings) one chi-square(2)
	// draw: its two-sided 99 % interval is [0.01, 10.6]; from below, D-SLAM
	// is conservative by design but a covariance five times the error's
	// (under 0.2 of the 2 dof) is a regression. Measured 1.48, with 99.3 %
	// of the landmarks inside their 95 % ellipse.
	const auto band = test::meanNeesBand(2, 1);
	EXPECT_LT(*a.landmark_nees_mean, band.upper);
	EXPECT_GT(*a.landmark_nees_mean, std::max(band.lower, 0.2 * 2));
	EXPECT_GE(*a.landmark_consistent_fraction, 0.95);
	// Not asserted: the pose NEES mean over steps, 16.1 measured, above even
	// the single-draw bound chi2_3(0.995) = 12.8: D-SLAM's localisation is
	// over-confident while it crosses the gaps (an open finding).
}

}  // namespace
