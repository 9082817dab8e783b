// D-SLAM's map-level association (book Sec. 3.4.2) after a long stretch of
// dead reckoning: the robot is uncertain by metres in the map frame, so the
// absolute gate, robot and map independent, passes features a grid spacing
// away. Anchors (measurements already tied to mapped features by tracking)
// must resolve what the absolute gate cannot:
//   1. a row shifted by one spacing is not accepted;
//   2. a measurement near a mapped feature in absolute terms, but far from
//      every mapped feature relative to the anchors, is a new feature.
// Measurements are exact (noise-free) so each decision is deterministic; the
// covariances are those of configs/sim/long_gap.ini after a crossing.

#include <esif/relative/FeatureMap.h>
#include <esif/relative/RelativeAssociation.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace
{
using namespace esif;
using namespace esif::relative;

constexpr double kRangeStd = 0.1, kBearingStd = M_PI / 180.0;  // the book's sensor, Sec. 1.3.3

Eigen::Matrix2d sensorCov() { return Eigen::Vector2d(kRangeStd * kRangeStd, kBearingStd * kBearingStd).asDiagonal(); }

/// Features at `xy`, known well relative to each other (5 cm) but sharing a
/// 1.7 m error of the whole region: mapped after a long crossing.
std::unique_ptr<FeatureMap> regionMap(const std::vector<Eigen::Vector2d>& xy)
{
	auto map = std::make_unique<FeatureMap>(SparseRecoveryParams{});
	PointSet points;
	const int n = static_cast<int>(xy.size());
	points.xy.resize(2 * n);
	Eigen::MatrixXd common(2 * n, 2);
	for (int i = 0; i < n; ++i)
	{
		points.xy.segment<2>(2 * i) = xy[i];
		common.middleRows<2>(2 * i) = Eigen::Matrix2d::Identity();
	}
	points.cov = 1.7 * 1.7 * common * common.transpose() + 0.05 * 0.05 * Eigen::MatrixXd::Identity(2 * n, 2 * n);
	std::vector<LandmarkId> ids(n);
	for (int i = 0; i < n; ++i) ids[i] = i;
	map->updateAnchor(ids, points);
	return map;
}

RangeBearing measure(const Pose2& robot, const Eigen::Vector2d& feature)
{
	const Eigen::Vector2d d = feature - robot.head<2>();
	RangeBearing m;
	m.range_m = d.norm();
	m.bearing_rad = std::remainder(std::atan2(d.y(), d.x()) - robot(2), 2 * M_PI);
	m.cov = sensorCov();
	return m;
}

Scan scanOf(const std::vector<RangeBearing>& ms)
{
	Scan s;
	s.max_range_m = 8;
	s.fov_rad = M_PI;
	s.measurements = ms;
	return s;
}

RelativeAssociationParams jcbbParams()
{
	RelativeAssociationParams p;
	p.association = AssociationMode::Jcbb;
	return p;
}

const Eigen::Matrix3d kRobotCov = Eigen::Vector3d(1.7 * 1.7, 1.7 * 1.7, std::pow(3.0 * M_PI / 180, 2)).asDiagonal();

// A row y = 3 m of five features 3 m apart. The robot is at the origin
// facing the row, but believes itself one spacing to the right.
struct ShiftedRow : ::testing::Test
{
	std::vector<Eigen::Vector2d> row = {{-6, 3}, {-3, 3}, {0, 3}, {3, 3}, {6, 3}};
	std::unique_ptr<FeatureMap> map = regionMap(row);
	Pose2 truth = Pose2(0, 0, M_PI / 2);
	Pose2 believed = Pose2(3, 0, M_PI / 2);
	RelativeAssociation association{jcbbParams(), ReferenceRules{}};
};

TEST_F(ShiftedRow, WithoutAnchorsTheTrueFeaturesAreNotFound)
{
	// The contrast the anchors exist for: every feature of the row is inside
	// the absolute gate (1.7 m), a shift by one spacing keeps every distance
	// and angle, and JCBB's hypothesis (here features 0 and 2, which the
	// relative test then drops) is not the truth (1 and 2).
	const Scan scan = scanOf({measure(truth, row[1]), measure(truth, row[2])});
	const StepReport r = association.associate(scan, believed, kRobotCov, *map);
	ASSERT_EQ(r.associations.size(), 2u);
	const auto is = [&](std::size_t i, LandmarkId id)
	{ return r.associations[i].kind == Association::Kind::Matched && r.associations[i].id == id; };
	EXPECT_FALSE(is(0, 1) && is(1, 2));
}

TEST_F(ShiftedRow, AnAnchorPicksTheTrueFeatures)
{
	// Feature 3 is tracked (held by the local SLAM), hence excluded.
	const Scan scan = scanOf({measure(truth, row[1]), measure(truth, row[2])});
	const std::vector<RelativeAssociation::Anchor> anchors = {{measure(truth, row[3]), 3}};
	const StepReport r = association.associate(scan, believed, kRobotCov, *map, {3}, anchors);
	ASSERT_EQ(r.associations.size(), 2u);
	EXPECT_EQ(r.associations[0].kind, Association::Kind::Matched);
	EXPECT_EQ(r.associations[0].id, 1);
	EXPECT_EQ(r.associations[1].kind, Association::Kind::Matched);
	EXPECT_EQ(r.associations[1].id, 2);
}

TEST_F(ShiftedRow, AnchorsThatDisagreeWithTheMapDecideNothing)
{
	// Two anchors whose measured distance (6 m) contradicts the map's (3 m):
	// no reference to test against, so nothing is matched or started.
	const Scan scan = scanOf({measure(truth, row[1])});
	const std::vector<RelativeAssociation::Anchor> anchors = {{measure(truth, row[2]), 2},
															  {measure(truth, row[4]), 3}};
	const StepReport r = association.associate(scan, truth, kRobotCov, *map, {2, 3}, anchors);
	ASSERT_EQ(r.associations.size(), 1u);
	EXPECT_EQ(r.associations[0].kind, Association::Kind::Rejected);
	EXPECT_EQ(association.anchorConflicts(), 1u);
}

TEST(RelativeAssociationNewFeature, NearAMappedFeatureButNotRelativeToTheAnchorsIsNew)
{
	// Mapped: a 3 x 2 grid. Seen: a feature 1.5 m from two mapped ones, well
	// inside the absolute new-feature gate (1.7 m robot error), with the
	// feature at the origin tracked as anchor.
	const std::vector<Eigen::Vector2d> grid = {{-3, 0}, {0, 0}, {3, 0}, {-3, 3}, {0, 3}, {3, 3}};
	const auto map = regionMap(grid);
	const Pose2 robot(0, -3, M_PI / 2);
	const Eigen::Vector2d fresh(1.5, 1.5);
	const Scan scan = scanOf({measure(robot, fresh)});
	RelativeAssociation association{jcbbParams(), ReferenceRules{}};

	const StepReport alone = association.associate(scan, robot, kRobotCov, *map, {1});
	// Without anchors the sighting is taken for a neighbour (one match has
	// no relative test) or left ambiguous; either way it is not mapped.
	EXPECT_NE(alone.associations[0].kind, Association::Kind::New);

	const std::vector<RelativeAssociation::Anchor> anchors = {{measure(robot, grid[1]), 1}};
	const StepReport anchored = association.associate(scan, robot, kRobotCov, *map, {1}, anchors);
	EXPECT_EQ(anchored.associations[0].kind, Association::Kind::New);
}

TEST(RelativeAssociationCandidates, MarginGrowsWithTheRobotUncertainty)
{
	// A mapped feature 4.4 m away, predicted 16 deg outside the 180 deg field
	// of view (the robot's heading error after dead reckoning); it is
	// measured just inside. With a fixed 10 deg margin it is no candidate
	// and the sighting would be mapped a second time; three standard
	// deviations of the predicted bearing (here about 25 deg) keep it.
	const Eigen::Vector2d feature(0, 0);
	const auto map = regionMap({feature, {30, 30}});
	const double predicted_bearing = M_PI / 2 + 16 * M_PI / 180;
	const Pose2 believed(4.4 * std::cos(predicted_bearing + M_PI), 4.4 * std::sin(predicted_bearing + M_PI), 0);
	const Pose2 truth(believed(0), believed(1), 20 * M_PI / 180);  // sees it at 86 deg
	const Scan scan = scanOf({measure(truth, feature)});
	ASSERT_LT(std::abs(scan.measurements[0].bearing_rad), M_PI / 2);

	RelativeAssociationParams fixed = jcbbParams();
	fixed.candidate_margin_sigmas = 0;
	RelativeAssociation narrow{fixed, ReferenceRules{}};
	EXPECT_NE(narrow.associate(scan, believed, kRobotCov, *map).associations[0].kind, Association::Kind::Matched);

	RelativeAssociation wide{jcbbParams(), ReferenceRules{}};
	const StepReport r = wide.associate(scan, believed, kRobotCov, *map);
	EXPECT_EQ(r.associations[0].kind, Association::Kind::Matched);
	EXPECT_EQ(r.associations[0].id, 0);
}

}  // namespace
