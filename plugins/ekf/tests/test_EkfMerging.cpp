// The EKF plugin merging landmarks (merge_landmarks_after_matches): the
// reports of the steps before a merge are rewritten at the end so that every
// matched measurement names a landmark of the final map.

#include <EsifTestSupport.h>
#include <TwoUnresolvedPoints.h>

#include <gtest/gtest.h>

namespace
{
using namespace esif;

std::vector<StepReport> replaySevenSteps(FilterPlugin& ekf)
{
	std::vector<StepReport> online;
	for (std::size_t k = 0; k < 7; ++k) online.push_back(ekf.processStep(test::standingBesideTwoUnresolvedPoints(k)));
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
