// SLSJF (book Ch. 5) end to end on the committed grid196 demo (Sec. 4.6.1
// scenario: 3000 steps, 196 features, local maps of 45 steps): accurate and
// consistent against the truth and the full-SLAM optimum, no wrong
// association without the rawlog's IDs, end poses more certain than the
// EKF's (Fig. 5.5), and with one-step maps and relinearisation the
// optimum of the local-map formulation is the full-SLAM optimum.

#include <EsifTestSupport.h>

#include <esif/association/Chi2.h>
#include <esif/config/ConfigFile.h>
#include <esif/eval/Evaluator.h>
#include <esif/formats/GroundTruth.h>
#include <esif/plugin/LocalMapJoiner.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <iostream>
#include <map>

namespace
{
using namespace esif;

const std::string kGrid196 = test::sourcePath("rawlogs/grid196.rawlog");

/// The [slsjf] section of a committed config, as INI text.
std::string sectionOf(const std::string& config)
{
	const std::string text = test::readText(test::sourcePath(config));
	return text.substr(text.find("[slsjf]") + std::string("[slsjf]").size());
}

/// The rawlog with the IDs of measurements closer than `min_range_m`
/// removed: the full-SLAM baseline skips measurements without an ID, so it
/// then uses exactly the measurements SLSJF's local maps use.
Rawlog withoutCloseRangeIds(Rawlog log, double min_range_m)
{
	for (auto& step : log.steps)
		if (step.scan)
			for (auto& m : step.scan->measurements)
				if (m.range_m < min_range_m) m.id.reset();
	return log;
}

struct Scored
{
	FilterPlugin::Ptr plugin;
	ReplayResult result;
	Accuracy accuracy;
	double shape_rmse_m = 0;  ///< landmark RMSE after the best rigid alignment with the truth
};

Scored run(const std::string& plugin_name, const std::string& section, const Rawlog& log)
{
	Scored r{test::makePlugin(plugin_name, section), {}, {}};
	r.result = replay(*r.plugin, log, {0, false});
	const auto truth = loadGroundTruth(groundTruthPrefixFor(kGrid196))->inInitialPoseFrame();
	const auto to_true = r.result.audit.filterToTrue();
	r.accuracy = evaluate(truth, r.result.record.trajectory, r.result.record.final_estimate, to_true);
	// The map's shape: what is left once its rotation and translation about
	// the initial pose, a single weakly observed quantity set by the first
	// scans, are fitted away (Eigen::umeyama without scaling).
	const auto& landmarks = r.result.record.final_estimate.landmarks;
	Eigen::MatrixXd est(2, landmarks.size()), tru(2, landmarks.size());
	for (std::size_t i = 0; i < landmarks.size(); ++i)
	{
		est.col(i) = landmarks[i].mean;
		tru.col(i) = truth.landmarks.at(to_true.at(landmarks[i].id));
	}
	const Eigen::MatrixXd T = Eigen::umeyama(est, tru, false);
	const Eigen::MatrixXd aligned = (T.topLeftCorner(2, 2) * est).colwise() + Eigen::Vector2d(T.topRightCorner(2, 1));
	r.shape_rmse_m = std::sqrt((aligned - tru).colwise().squaredNorm().mean());
	return r;
}

void print(const std::string& what, const Scored& r)
{
	std::cout << what << ": landmark RMSE " << *r.accuracy.landmark_rmse_m << " m (shape " << r.shape_rmse_m
			  << " m), ATE " << *r.accuracy.ate_rmse_m << " m, landmark NEES " << *r.accuracy.landmark_nees_mean
			  << ", consistent " << *r.accuracy.landmark_consistent_fraction << "\n";
}

TEST(SlsjfGrid196, AsAccurateAsTheOptimumOnTheSameMeasurementsAndConsistent)
{
	const Rawlog log = readRawlog(kGrid196);
	const std::string section = sectionOf("configs/slsjf.ini");
	const Scored plain = run("Slsjf", section, log);
	const Scored smoothed = run("Slsjf", section + "\nsmoothing = final\n", log);
	const Scored optimum = run("CeresFullSlam", "", withoutCloseRangeIds(log, 0.3));
	print("SLSJF", plain);
	print("SLSJF smoothed", smoothed);
	print("full SLAM, same measurements", optimum);
	EXPECT_EQ(plain.result.record.final_estimate.landmarks.size(), 164u);
	// Every map on the same measurements estimates the same shape: SLSJF's
	// within 1.2x of the optimum's (measured 1.02x). The whole map's rotation
	// about the start is set by the first scans alone and differs between
	// estimators by a fraction of its own sigma; it dominates the raw RMSE of
	// one run, so the raw figure is bounded through consistency instead.
	EXPECT_LE(plain.shape_rmse_m, 1.2 * optimum.shape_rmse_m);
	EXPECT_LE(smoothed.shape_rmse_m, 1.2 * optimum.shape_rmse_m);
	EXPECT_GE(*plain.accuracy.landmark_consistent_fraction, 0.95);
	EXPECT_GE(*smoothed.accuracy.landmark_consistent_fraction, 0.95);
	// Relinearised, SLSJF is the optimum of the local-map formulation: its raw
	// error is the full-SLAM optimum's within the 1.2x (measured 1.17x).
	EXPECT_LE(*smoothed.accuracy.landmark_rmse_m, 1.2 * *optimum.accuracy.landmark_rmse_m);
	// Relinearised, every step's pose is re-estimated from its map's final
	// start pose (smoothedTrajectory): better than the online poses, and
	// consistent (pose NEES below its 95% bound at 95% of the steps).
	EXPECT_LT(*smoothed.accuracy.ate_rmse_m, *plain.accuracy.ate_rmse_m);
	EXPECT_GE(*smoothed.accuracy.pose_consistent_fraction, 0.95);
	EXPECT_EQ(plain.result.audit.wrongCount(), 0u);
}

TEST(SlsjfGrid196, WithoutIdsMakesNoWrongAssociation)
{
	RawlogReadOptions hidden;
	hidden.hide_landmark_ids = true;
	const Scored r = run("Slsjf", sectionOf("configs/slsjf_jcbb.ini"), readRawlog(kGrid196, hidden));
	const auto& audit = r.result.audit;
	print("SLSJF, JCBB", r);
	std::cout << "  " << audit.newCount() << " new, " << audit.matchedCount() << " matched, " << audit.rejectedCount()
			  << " rejected, " << audit.wrongCount() << " wrong\n";
	EXPECT_EQ(audit.wrongCount(), 0u);
	// One global landmark per true feature: none split, none merged.
	EXPECT_EQ(r.result.record.final_estimate.landmarks.size(), 164u);
	EXPECT_EQ(audit.filterToTrue().size(), 164u);
	EXPECT_GE(*r.accuracy.landmark_consistent_fraction, 0.95);
}

TEST(SlsjfGrid196, WithoutIdsScansAssociatedWithTheGlobalMapMakeNoWrongAssociation)
{
	// The same, each local map's scans associated with the global features
	// within 12 m of its start: the 5 m sensor range plus a local map's
	// travel (45 steps of 0.15 m), as the key's documentation asks. The
	// association filter decides, the map level checks the IDs.
	RawlogReadOptions hidden;
	hidden.hide_landmark_ids = true;
	const Scored r = run("Slsjf", sectionOf("configs/slsjf_jcbb.ini") + "\nlocal_map_global_features_radius_m = 12\n",
						 readRawlog(kGrid196, hidden));
	const auto& audit = r.result.audit;
	print("SLSJF, JCBB scan by scan against the global map", r);
	EXPECT_EQ(audit.wrongCount(), 0u);
	EXPECT_EQ(r.result.record.final_estimate.landmarks.size(), 164u);
	EXPECT_EQ(audit.filterToTrue().size(), 164u);
	EXPECT_GE(*r.accuracy.landmark_consistent_fraction, 0.95);
	// The path is taken: revisited features start local features under their global IDs.
	const auto counters = r.plugin->costFigures().counters;
	const auto started = std::find_if(counters.begin(), counters.end(),
									  [](const auto& c) { return c.first == "local_features_started_from_global"; });
	ASSERT_NE(started, counters.end());
	EXPECT_GT(started->second, 100.0);
}

TEST(SlsjfGrid196, EndHeadingsAreMoreCertainThanTheEkfsAndPositionsAsCertain)
{
	// Fig. 5.5: SLSJF keeps every local map's end pose, and each is smoothed
	// by all later maps, so its 2-sigma bounds are smaller than the EKF's
	// (which only the past informs) at the same steps; both consistent.
	// Both filters with first-estimates Jacobians, as configs/slsjf.ini and
	// configs/ekf.ini: with the textbook ones each gains spurious
	// information, and the comparison would be between over-confidences.
	const Rawlog log = readRawlog(kGrid196);
	const Scored slsjf = run("Slsjf", sectionOf("configs/slsjf.ini"), log);
	const Scored ekf = run("EkfSlam", "association = known_ids\njacobians = first_estimates\n", log);
	const auto ends = dynamic_cast<const LocalMapJoiner&>(*slsjf.plugin).endPoses();
	const auto truth = loadGroundTruth(groundTruthPrefixFor(kGrid196))->inInitialPoseFrame();
	const std::size_t steps_per_map = 45;
	std::size_t smaller = 0, compared = 0, slsjf_consistent = 0;
	double worst_position_ratio = 0;
	for (std::size_t k = 1; k < ends.size(); ++k)  // the last map is partial
	{
		const std::size_t step = k * steps_per_map - 1;
		const Eigen::Matrix3d& P = ends[k - 1].cov;
		const Eigen::Matrix3d& Q = ekf.result.record.trajectory[step].pose.cov;
		smaller += P(2, 2) < Q(2, 2);
		worst_position_ratio = std::max({worst_position_ratio, P(0, 0) / Q(0, 0), P(1, 1) / Q(1, 1)});
		Eigen::Vector3d e = ends[k - 1].mean - truth.path[step];
		e(2) = wrapAngle(e(2));
		slsjf_consistent += *nees(e, P) < chi2Quantile(0.95, 3);
		++compared;
	}
	std::cout << "end poses with smaller heading variance than the EKF's: " << smaller << " of " << compared
			  << ", largest x or y variance ratio to the EKF's " << worst_position_ratio
			  << "; within their 95% ellipsoid: " << slsjf_consistent << "\n";
	EXPECT_EQ(smaller, compared);
	// In x and y both are dominated by the drift both filters share; the
	// first-estimates fusion gives up a little information for consistency
	// (measured: at most 4.5% more variance than the EKF's; with the
	// book's current-estimate fusion every variance was smaller, and the
	// landmarks over-confident).
	EXPECT_LT(worst_position_ratio, 1.10);
	EXPECT_GE(slsjf_consistent, compared * 9 / 10);
}

}  // namespace
