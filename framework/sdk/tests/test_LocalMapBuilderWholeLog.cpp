/// \file test_LocalMapBuilderWholeLog.cpp
/// With every close limit 0 the local-map builder makes the whole of
/// rawlogs/grid196.rawlog one local map. That map is the EKF plugin's
/// estimate: both run the framework's LandmarkEkf with the same association
/// and noise, so they must agree to round-off, with landmark IDs and with
/// JCBB on hidden IDs alike.

#include <EsifTestSupport.h>
#include <LocalMapBuilderTestSupport.h>

#include <esif/formats/RawlogReader.h>
#include <esif/localmap/LocalMapBuilder.h>
#include <esif/run/Replay.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace
{
using namespace esif;
namespace tb = esif::test::builder;

const std::string kGrid196 = test::sourcePath("rawlogs/grid196.rawlog");

/// Same code (LandmarkEkf) on the same input: only the builder's own-ID
/// numbering (from 1, the plugin's from 0) differs, which touches no
/// arithmetic, so the numbers should be identical; 1e-12 m (m^2, rad) allows
/// for a reordering of floating-point operations by the compiler between the
/// two call sites, a few ulps of the 40 m coordinates and of the covariances.
constexpr double kTol = 1e-12;

void expectBuilderEqualsEkfPlugin(bool hide_ids, EkfAssociation association, const std::string& ekf_section)
{
	RawlogReadOptions opts;
	opts.hide_landmark_ids = hide_ids;
	const Rawlog log = readRawlog(kGrid196, opts);

	auto ekf = test::makePlugin("EkfSlam", ekf_section);
	const ReplayResult plugin = replay(*ekf, log, {0, false});

	LocalMapBuilderParams params;
	params.local_map_steps = 0;
	params.local_map_max_features = 0;
	params.local_map_max_distance_m = 0;
	params.association.association = association;
	const auto built = tb::buildLocalMaps(params, log.steps);
	ASSERT_EQ(built.maps.size(), 1u);
	const LocalMap& map = built.maps[0];
	EXPECT_EQ(map.steps, log.steps.size());
	EXPECT_TRUE(built.last_from_finish);

	// IDs the filters numbered themselves start at 1 in the builder, 0 in the plugin.
	const LandmarkId offset = hide_ids ? 1 : 0;

	// Every association decision.
	ASSERT_EQ(plugin.reports.size(), map.step_reports.size());
	std::size_t decisions = 0;
	for (std::size_t s = 0; s < map.step_reports.size(); ++s)
	{
		const auto& a = map.step_reports[s].associations;
		const auto& b = plugin.reports[s].associations;
		ASSERT_EQ(a.size(), b.size()) << "step " << s;
		for (std::size_t i = 0; i < a.size(); ++i)
		{
			EXPECT_EQ(a[i].kind, b[i].kind) << "step " << s << " measurement " << i;
			if (a[i].kind != Association::Kind::Rejected)
			{
				EXPECT_EQ(a[i].id, b[i].id + offset);
			}
			++decisions;
		}
	}

	// Robot pose and covariance.
	const auto& est = plugin.record.final_estimate;
	const Pose2 robot = est.robot.mean;
	const double pose_dev = std::max((map.end_pose.head<2>() - robot.head<2>()).cwiseAbs().maxCoeff(),
									 std::abs(wrapAngle(map.end_pose.z() - robot.z())));
	const double pose_cov_dev = (map.covariance->topLeftCorner<3, 3>() - est.robot.cov).cwiseAbs().maxCoeff();

	// Landmarks, in creation order: mean and marginal covariance.
	ASSERT_EQ(map.features.size(), est.landmarks.size());
	double feature_dev = 0, feature_cov_dev = 0;
	for (std::size_t i = 0; i < map.features.size(); ++i)
	{
		EXPECT_EQ(map.features[i].id, est.landmarks[i].id + offset);
		feature_dev = std::max(feature_dev, (map.features[i].position - est.landmarks[i].mean).cwiseAbs().maxCoeff());
		feature_cov_dev = std::max(
			feature_cov_dev,
			(map.covariance->block<2, 2>(3 + 2 * i, 3 + 2 * i) - est.landmarks[i].cov).cwiseAbs().maxCoeff());
	}
	std::cout << (hide_ids ? "hidden IDs, jcbb" : "known IDs") << ": " << map.features.size() << " features, "
			  << decisions << " association decisions; largest deviation from the EKF plugin: pose " << pose_dev
			  << ", features " << feature_dev << ", pose covariance " << pose_cov_dev << ", feature covariances "
			  << feature_cov_dev << "\n";
	EXPECT_LT(pose_dev, kTol);
	EXPECT_LT(feature_dev, kTol);
	EXPECT_LT(pose_cov_dev, kTol);
	EXPECT_LT(feature_cov_dev, kTol);
	EXPECT_NO_THROW(map.validate("test"));
}

TEST(LocalMapBuilderWholeLog, KnownIdsEqualsTheEkfPlugin)
{
	expectBuilderEqualsEkfPlugin(false, EkfAssociation::KnownIds, "association = known_ids\n");
}

TEST(LocalMapBuilderWholeLog, JcbbOnHiddenIdsEqualsTheEkfPlugin)
{
	expectBuilderEqualsEkfPlugin(true, EkfAssociation::Jcbb, "association = jcbb\n");
}

}  // namespace
