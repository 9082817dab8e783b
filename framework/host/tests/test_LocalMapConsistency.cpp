// One local map held against a reference in its start frame
// (eval/LocalMapConsistency.h): the frame change, the NEES parts, and a
// feature the reference does not know.
#include <LocalMapTestSupport.h>

#include <esif/eval/LocalMapConsistency.h>

#include <gtest/gtest.h>

#include <cmath>

namespace esif
{
namespace
{
/// A map of two features seen from start pose `start`, exactly where the
/// reference has them, with 0.1 m / 0.1 rad standard deviations.
struct Scene
{
	Pose2 start{5, -2, M_PI / 2};
	Pose2 end_local{2, 0.5, 0.2};
	Eigen::Vector2d f1_local{1, 1}, f2_local{3, -1};
	Pose2 end() const { return compose(start, end_local); }
	Eigen::Vector2d global(const Eigen::Vector2d& p) const { return compose(start, Pose2(p.x(), p.y(), 0)).head<2>(); }
	LocalMap map() const
	{
		return test::makeLocalMap(
			4, end_local, {{1, f1_local.x(), f1_local.y()}, {2, f2_local.x(), f2_local.y()}}, 0.1);
	}
	std::map<LandmarkId, Eigen::Vector2d> landmarks() const { return {{1, global(f1_local)}, {2, global(f2_local)}}; }
};
}  // namespace

TEST(LocalMapConsistency, AMapWhereTheReferenceIsHasZeroNeesWhateverItsStartPose)
{
	const Scene s;
	const auto c = localMapConsistency(s.map(), s.start, s.end(), s.landmarks());
	EXPECT_EQ(c.index, 4u);
	EXPECT_EQ(c.whole.dof, 7u);
	EXPECT_NEAR(c.whole.nees, 0, 1e-9);
	EXPECT_NEAR(c.end_pose_nees, 0, 1e-9);
	EXPECT_EQ(c.features_compared, 2u);
	EXPECT_DOUBLE_EQ(*c.features_inside_fraction, 1.0);
}

TEST(LocalMapConsistency, ErrorsAreMeasuredInTheStartFrame)
{
	const Scene s;
	LocalMap map = s.map();
	map.end_pose(2) += 0.3;	 // 3 sigma in heading
	map.features[1].position.x() += 0.5;  // 5 sigma: outside its 95% ellipse
	const auto c = localMapConsistency(map, s.start, s.end(), s.landmarks());
	EXPECT_NEAR(c.end_pose_nees, 9, 1e-9);
	EXPECT_NEAR(c.end_heading_error_rad, 0.3, 1e-12);
	EXPECT_NEAR(c.whole.nees, 9 + 25, 1e-9);
	EXPECT_DOUBLE_EQ(*c.features_inside_fraction, 0.5);
	EXPECT_FALSE(c.whole.consistent());
}

TEST(LocalMapConsistency, AFeatureTheReferenceLacksIsMarginalised)
{
	const Scene s;
	auto landmarks = s.landmarks();
	landmarks.erase(2);
	const auto c = localMapConsistency(s.map(), s.start, s.end(), landmarks);
	EXPECT_EQ(c.features_compared, 1u);
	EXPECT_EQ(c.whole.dof, 5u);
	EXPECT_EQ(c.whole.variables_marginalised, 1u);
}

}  // namespace esif
