// Scoring runs on local maps: accuracy against the ground truth beside the
// maps (end poses paired by k), the difference from a reference result
// (zero for itself, a shift for a shifted one, headings modulo 2 pi), and
// the folder summary's check of maps sharing fewer than two features.

#include <LocalMapTestSupport.h>

#include <esif/eval/LocalMapEvaluation.h>
#include <esif/eval/LocalMapFolderSummary.h>
#include <esif/eval/ReferenceResultDifference.h>

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using esif::Pose2;
using esif::test::makeLocalMap;

/// Two landmarks and three end poses of a run.
struct RunFixture
{
	esif::Estimate estimate;
	std::vector<esif::TrajectoryPoint> end_poses;
	std::map<esif::LandmarkId, esif::LandmarkId> identity{{4, 4}, {9, 9}};

	RunFixture()
	{
		estimate.landmarks = {{4, Eigen::Vector2d(1, 2), Eigen::Matrix2d::Identity() * 0.01},
							  {9, Eigen::Vector2d(-3, 5), Eigen::Matrix2d::Identity() * 0.01}};
		for (std::size_t k = 1; k <= 3; ++k)
		{
			esif::PoseEstimate p;
			p.mean = Pose2(static_cast<double>(k), 0, 3.0);	// heading near pi
			p.cov = Eigen::Matrix3d::Identity() * 0.01;
			end_poses.push_back({k, static_cast<double>(k), p});
		}
	}

	/// The run's own result, moved by (dx, dy) and with headings + dphi.
	esif::ReferenceResult asReference(double dx, double dy, double dphi) const
	{
		esif::ReferenceResult ref;
		for (const auto& lm : estimate.landmarks) ref.features[lm.id] = lm.mean + Eigen::Vector2d(dx, dy);
		for (const auto& p : end_poses) ref.end_poses[p.step] = Pose2(p.pose.mean.x() + dx, p.pose.mean.y() + dy, p.pose.mean(2) + dphi);
		return ref;
	}
};

TEST(ReferenceResultDifference, ItselfGivesZero)
{
	const RunFixture run;
	const auto d = esif::referenceResultDifference(run.estimate, run.end_poses, run.identity, run.asReference(0, 0, 0));
	EXPECT_EQ(d.landmarks_matched, 2u);
	EXPECT_EQ(d.poses_matched, 3u);
	EXPECT_DOUBLE_EQ(*d.landmark_rms_m, 0.0);
	EXPECT_DOUBLE_EQ(*d.landmark_max_m, 0.0);
	EXPECT_DOUBLE_EQ(*d.pose_rms_m, 0.0);
	EXPECT_DOUBLE_EQ(*d.heading_rms_deg, 0.0);
}

TEST(ReferenceResultDifference, AShiftGivesThatShiftAndHeadingsCountModuloTwoPi)
{
	const RunFixture run;
	// Unwrapped headings (as the authors' pose.txt): + 4 pi is no difference,
	// and 3.0 against 3.0 + 0.4 - 2 pi is 0.4 rad across the wrap.
	auto d = esif::referenceResultDifference(run.estimate, run.end_poses, run.identity, run.asReference(0.3, -0.4, 4 * M_PI));
	EXPECT_NEAR(*d.landmark_rms_m, 0.5, 1e-12);
	EXPECT_NEAR(*d.landmark_max_m, 0.5, 1e-12);
	EXPECT_NEAR(*d.pose_rms_m, 0.5, 1e-12);
	EXPECT_NEAR(*d.pose_max_m, 0.5, 1e-12);
	EXPECT_NEAR(*d.heading_rms_deg, 0.0, 1e-9);
	d = esif::referenceResultDifference(run.estimate, run.end_poses, run.identity, run.asReference(0, 0, 0.4 - 2 * M_PI));
	EXPECT_NEAR(*d.heading_rms_deg, 0.4 * 180 / M_PI, 1e-9);
}

TEST(ReferenceResultDifference, LandmarksArePairedThroughTheFileIds)
{
	const RunFixture run;
	// The plugin numbered its landmarks 4 and 9; they stand for file features 40 and 90.
	const auto reference = [] {
		esif::ReferenceResult ref;
		ref.features[40] = Eigen::Vector2d(1, 3);  // 1 m from the run's landmark 4
		ref.features[77] = Eigen::Vector2d(0, 0);  // no landmark of the run
		return ref;
	}();
	const auto d = esif::referenceResultDifference(run.estimate, run.end_poses, {{4, 40}, {9, 90}}, reference);
	EXPECT_EQ(d.landmarks_matched, 1u);
	EXPECT_NEAR(*d.landmark_rms_m, 1.0, 1e-12);
	EXPECT_EQ(d.poses_matched, 0u);
	EXPECT_FALSE(d.pose_rms_m.has_value());
	esif::Stats stats;
	esif::setReferenceResultStats(stats, d);
	EXPECT_EQ(stats.items().size(), esif::referenceResultKeys().size());
	EXPECT_FALSE(stats.number("refres_pose_rms_m").has_value());
	EXPECT_DOUBLE_EQ(*stats.number("refres_landmarks_matched"), 1.0);
}

TEST(LocalMapEvaluation, EndPosesArePairedByMapIndex)
{
	const RunFixture run;
	esif::LocalMapFolder folder;
	folder.truth_landmarks = std::map<esif::LandmarkId, Eigen::Vector2d>{{4, Eigen::Vector2d(1, 2.1)}};
	// Truth of maps 2 and 3 only: 0.2 m off at k = 3.
	folder.truth_end_poses = std::map<std::size_t, Pose2>{{2, Pose2(2, 0, 3.0)}, {3, Pose2(3, 0.2, 3.0)}};
	const auto acc = esif::evaluateLocalMapRun(folder, run.end_poses, run.estimate, run.identity);
	ASSERT_TRUE(acc.has_value());
	EXPECT_EQ(acc->landmarks_evaluated, 1u);
	EXPECT_NEAR(*acc->landmark_rmse_m, 0.1, 1e-12);
	EXPECT_EQ(acc->poses_evaluated, 2u);
	EXPECT_NEAR(*acc->ate_rmse_m, std::sqrt(0.04 / 2), 1e-12);
	EXPECT_NEAR(*acc->landmark_nees_mean, 1.0, 1e-9);  // 0.1^2 / 0.01

	const auto truth = esif::localMapGroundTruth(folder);
	ASSERT_TRUE(truth.has_value());
	EXPECT_EQ(truth->path.size(), 2u);
	EXPECT_FALSE(esif::evaluateLocalMapRun(esif::LocalMapFolder{}, run.end_poses, run.estimate, run.identity));
}

TEST(LocalMapFolderSummary, CountsAndMapsSharingFewerThanTwoFeatures)
{
	esif::LocalMapFolder folder;
	folder.maps = {makeLocalMap(1, Pose2(1, 0, 0), {{1, 1, 1}, {2, 2, 2}, {3, 3, 3}}),
				   makeLocalMap(2, Pose2(1, 0, 0), {{1, 1, 1}, {4, 2, 2}}),	 // shares 1
				   makeLocalMap(3, Pose2(1, 0, 0), {{2, 1, 1}, {4, 2, 2}}),	 // shares 2
				   makeLocalMap(4, Pose2(1, 0, 0), {{5, 1, 1}})};  // shares none
	const auto s = esif::summarizeLocalMapFolder(folder);
	EXPECT_EQ(s.maps, 4u);
	EXPECT_EQ(s.state_dim_min, 5u);
	EXPECT_EQ(s.state_dim_max, 9u);
	EXPECT_DOUBLE_EQ(s.state_dim_mean, (9.0 + 7 + 7 + 5) / 4);
	EXPECT_EQ(s.feature_entries, 8u);
	EXPECT_EQ(s.distinct_ids, 5u);
	ASSERT_EQ(s.weakly_linked.size(), 2u);
	EXPECT_EQ(esif::weaklyLinkedText(s.weakly_linked[0]), "map 2 shares 1 feature with map 1");
	EXPECT_EQ(esif::weaklyLinkedText(s.weakly_linked[1]), "map 4 shares 0 features with maps 1-3");
	const std::string text = esif::localMapFolderInfoText(s, "DIR");
	EXPECT_NE(text.find("DIR: 4 local maps\n"), std::string::npos) << text;
	EXPECT_NE(text.find("state dimension min/mean/max: 5 / 7.0 / 9"), std::string::npos) << text;
	EXPECT_NE(text.find("ground truth: none"), std::string::npos) << text;
}

}  // namespace
