// The EKF plugin merging landmarks (merge_landmarks_after_matches): the
// reports of the steps before a merge are rewritten at the end so that every
// matched measurement names a landmark of the final map.

#include <EsifTestSupport.h>

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using namespace esif;

/// Step k of a robot standing still that sees two points 0.15 m apart along
/// one bearing with 0.3 m range noise (the sensor cannot resolve them in a
/// few sightings).
StepInput standingStillBesideTwoPoints(std::size_t k)
{
	StepInput s;
	s.index = k;
	if (k > 0) s.odometry = OdometryIncrement{{0, 0, 0}, Eigen::Vector3d(1e-6, 1e-6, 1e-8).asDiagonal()};
	Scan scan;
	for (const double range : {3.0, 3.15})
		scan.measurements.push_back({range, 0.0, Eigen::Vector2d(0.09, std::pow(M_PI / 180, 2)).asDiagonal(), {}});
	s.scan = scan;
	return s;
}

std::vector<StepReport> replaySevenSteps(FilterPlugin& ekf)
{
	std::vector<StepReport> online;
	for (std::size_t k = 0; k < 7; ++k) online.push_back(ekf.processStep(standingStillBesideTwoPoints(k)));
	ekf.finish();
	return online;
}

TEST(EkfMerging, EarlierReportsNameTheLandmarkAMergedOneBecame)
{
	auto ekf = test::makePlugin("EkfSlam", "association = jcbb\nupdate_iterations = 1\nmerge_landmarks_after_matches = 5\n");
	const auto online = replaySevenSteps(*ekf);
	const auto final_reports = ekf->finalReports();
	ASSERT_TRUE(final_reports);
	ASSERT_EQ(final_reports->size(), online.size());
	const auto estimate = ekf->estimate();
	ASSERT_EQ(estimate.landmarks.size(), 1u);
	const LandmarkId kept = estimate.landmarks.front().id;
	// Online, step 0 started two landmarks; finally both are the kept one.
	EXPECT_NE(online[0].associations[0].id, online[0].associations[1].id);
	for (const auto& report : *final_reports)
		for (const auto& a : report.associations) EXPECT_EQ(a.id, kept);
	EXPECT_EQ(test::countersOf(*ekf).at("landmark_merges"), 1);
}

TEST(EkfMerging, WithoutMergingTheOnlineReportsStand)
{
	auto ekf = test::makePlugin("EkfSlam", "association = jcbb\nupdate_iterations = 1\n");
	replaySevenSteps(*ekf);
	EXPECT_FALSE(ekf->finalReports());
	EXPECT_EQ(ekf->estimate().landmarks.size(), 2u);
	EXPECT_EQ(test::countersOf(*ekf).at("landmark_merges"), 0);
}

}  // namespace
