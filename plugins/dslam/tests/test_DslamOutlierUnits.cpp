// Units of D-SLAM's outlier handling: the re-observation gate's innovation
// (OutlierGate: reobservationDistance2) and the tracking stage of association
// without IDs (HeldFeatureTracking). The second-sighting confirmation of new
// features is the SDK's TentativeFeatures (framework/sdk/tests/test_TentativeFeatures.cpp).

#include "HeldFeatureTracking.h"
#include "OutlierGate.h"

#include <esif/association/Chi2.h>
#include <esif/models/RangeBearingModel.h>

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

namespace
{
using namespace esif;
using namespace esif::dslam;

const double kGate = chi2Quantile(0.999, 2);  // 13.8

TEST(DslamReobservationGate, DistanceMatchesSampledInnovationStatistics)
{
	// The innovation of a true measurement, robot and feature drawn from
	// their covariances, has chi-square(2) statistics: mean d2 = 2 and 0.1%
	// beyond the 0.999 gate. 20,000 draws: the mean within 3% (its standard
	// error is 2/sqrt(20000) = 0.014, i.e. 0.7%, plus linearisation error at
	// 0.05 rad heading sigma), the tail within 0.05-0.3%.
	const Pose2 robot(2.0, 1.0, 0.3), sensor(0.2, 0.0, 0.0);
	const Eigen::Vector2d feature(5.0, 3.0);
	Eigen::Matrix3d Pr;
	Pr << 0.04, 0.01, 0.0, 0.01, 0.09, 0.002, 0.0, 0.002, 0.0025;
	Eigen::Matrix2d Pf;
	Pf << 0.05, -0.01, -0.01, 0.03;
	const Eigen::Matrix2d R = Eigen::Vector2d(0.01, std::pow(M_PI / 180, 2)).asDiagonal();
	std::mt19937 rng(3);
	std::normal_distribution<double> n01;
	const auto draw = [&](const auto& cov)
	{
		using V = Eigen::Matrix<double, std::decay_t<decltype(cov)>::RowsAtCompileTime, 1>;
		V e;
		for (int i = 0; i < e.size(); ++i) e(i) = n01(rng);
		return V(cov.llt().matrixL() * e);
	};
	double sum = 0;
	int beyond = 0;
	const int n = 20000;
	for (int k = 0; k < n; ++k)
	{
		const Pose2 true_robot = robot - draw(Pr);
		const Eigen::Vector2d true_feature = feature - draw(Pf);
		Eigen::Vector2d z = predictRangeBearing(true_robot, sensor, true_feature).z + draw(R);
		const double d2 = reobservationDistance2(robot, Pr, sensor, feature, Pf, {1, z, R});
		sum += d2;
		beyond += d2 > kGate;
	}
	EXPECT_NEAR(sum / n, 2.0, 0.06);
	EXPECT_GT(beyond, n * 0.0005);
	EXPECT_LT(beyond, n * 0.003);
}

const Eigen::Matrix2d kSensorNoise = Eigen::Vector2d(0.01, std::pow(M_PI / 180, 2)).asDiagonal();

/// Range and bearing of (x, y) from a robot and sensor at the origin.
Eigen::Vector2d rangeBearingOf(double x, double y)
{
	return predictRangeBearing(Pose2(0, 0, 0), Pose2(0, 0, 0), {x, y}).z;
}

/// A scan of the points `xy`, exact, with the noise kSensorNoise.
Scan scanOf(const std::vector<std::pair<double, double>>& xy)
{
	Scan scan;
	for (const auto& [x, y] : xy)
	{
		const Eigen::Vector2d z = rangeBearingOf(x, y);
		RangeBearing m;
		m.range_m = z(0);
		m.bearing_rad = z(1);
		m.cov = kSensorNoise;
		scan.measurements.push_back(m);
	}
	return scan;
}

TEST(DslamHeldFeatureTracking, MatchesTheHeldFeatureNotItsGridNeighbour)
{
	// The robot is 1.5 m uncertain across its path, as after a stretch without
	// features, but it has just seen the features at (3, 0) and (3, 3): the
	// local SLAM holds them with that same error. A measurement of (3, 3)
	// must go to (3, 3), not to (3, 0) or to nothing.
	LocalSlam local;
	local.predict({Pose2(0, 0, 0), Eigen::Vector3d(0.0004, 2.25, 0.0001).asDiagonal()});
	local.addFeatures({{10, rangeBearingOf(3, 0), kSensorNoise}, {11, rangeBearingOf(3, 3), kSensorNoise}},
					  Pose2(0, 0, 0));

	const Scan scan = scanOf({{3.0, 3.0}, {6.0, 0.0}});
	const auto tracked = trackHeldFeatures(local, scan, true, 0.99, CandidateWindow(scan, 2.0, 10.0), {});
	ASSERT_EQ(tracked.size(), 2u);
	ASSERT_TRUE(tracked[0].feature.has_value());
	EXPECT_EQ(*tracked[0].feature, 11);
	EXPECT_NEAR(tracked[0].min_distance2, 0.0, 1e-6);
	EXPECT_FALSE(tracked[1].feature.has_value());  // (6, 0): a feature the local SLAM does not hold
}

TEST(DslamHeldFeatureTracking, LeavesHeldFeaturesOutOfViewOutOfTheCandidates)
{
	// After a blind turn the heading is uncertain by 1.5 rad (86 deg), and the
	// local SLAM still holds a pair of cylinders 0.2 m apart behind the robot.
	// A new pair of the same shape ahead, 3 m off in a 60 deg camera, fits the
	// held pair turned by 180 deg within the individual gate (d2 about
	// pi^2 / 1.5^2 = 4.4 < 9.2), and JCBB cannot tell equal pairs apart. The
	// predicted pose places the held pair out of view: no candidates. Each
	// measurement still reports that distance, so D-SLAM leaves it out as
	// ambiguous rather than mapping it as new.
	LocalSlam local;
	local.addFeatures({{10, rangeBearingOf(-3, -0.1), kSensorNoise}, {11, rangeBearingOf(-3, 0.1), kSensorNoise}},
					  Pose2(0, 0, 0));
	local.predict({Pose2(0, 0, 0), Eigen::Vector3d(1e-4, 1e-4, 1.5 * 1.5).asDiagonal()});

	Scan scan = scanOf({{3.0, 0.1}, {3.0, -0.1}});
	scan.max_range_m = 5;
	scan.fov_rad = 60 * M_PI / 180;
	const auto in_view = trackHeldFeatures(local, scan, true, 0.99, CandidateWindow(scan, 2.0, 10.0), {});
	ASSERT_EQ(in_view.size(), 2u);
	for (const auto& t : in_view)
	{
		EXPECT_FALSE(t.feature.has_value());
		EXPECT_GT(t.min_distance2, 3.0);
		EXPECT_LT(t.min_distance2, 6.0);
	}

	// The same scan from a sensor of unknown field of view: the held pair is a
	// candidate and JCBB takes it (what the window prevents).
	Scan unbounded = scan;
	unbounded.fov_rad = 0;
	const auto tracked = trackHeldFeatures(local, unbounded, true, 0.99, CandidateWindow(unbounded, 2.0, 10.0), {});
	ASSERT_EQ(tracked.size(), 2u);
	EXPECT_TRUE(tracked[0].feature.has_value() && tracked[1].feature.has_value());
}

TEST(DslamHeldFeatureTracking, AFeatureInViewIsFoundBesideOneHeldOutOfView)
{
	// The local SLAM holds a feature behind the robot (first) and one ahead
	// (second): only the second is a candidate, and a sighting of it gets
	// its ID, with the distance to it, not to the one behind.
	LocalSlam local;
	local.addFeatures({{20, rangeBearingOf(-3, 0), kSensorNoise}, {21, rangeBearingOf(3, 0.5), kSensorNoise}},
					  Pose2(0, 0, 0));
	local.predict({Pose2(0, 0, 0), Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal()});
	Scan scan = scanOf({{3.0, 0.5}});
	scan.max_range_m = 5;
	scan.fov_rad = 60 * M_PI / 180;
	const auto tracked = trackHeldFeatures(local, scan, true, 0.99, CandidateWindow(scan, 2.0, 10.0), {});
	ASSERT_EQ(tracked.size(), 1u);
	ASSERT_TRUE(tracked[0].feature.has_value());
	EXPECT_EQ(*tracked[0].feature, 21);
	EXPECT_LT(tracked[0].min_distance2, 0.01);
}

TEST(DslamLocalSlam, PredictionOfSomeHeldFeaturesIsTheirPartOfThePredictionOfAll)
{
	LocalSlam local;
	local.addFeatures({{20, rangeBearingOf(-3, 0), kSensorNoise}, {21, rangeBearingOf(3, 0.5), kSensorNoise},
					   {22, rangeBearingOf(4, -1), kSensorNoise}},
					  Pose2(0, 0, 0));
	local.predict({Pose2(0.5, 0, 0.1), Eigen::Vector3d(0.01, 0.02, 0.003).asDiagonal()});
	const Pose2 sensor(0.1, 0, 0);
	const LocalSlam::HeldPrediction all = local.predictHeld({0, 1, 2}, sensor, kSensorNoise);
	const LocalSlam::HeldPrediction some = local.predictHeld({2, 0}, sensor, kSensorNoise);
	ASSERT_EQ(some.predictions.rows(), 2);
	EXPECT_EQ(some.predictions.row(0), all.predictions.row(2));
	EXPECT_EQ(some.predictions.row(1), all.predictions.row(0));
	EXPECT_LT((some.covariance.block<2, 2>(0, 0) - all.covariance.block<2, 2>(4, 4)).norm(), 1e-15);
	EXPECT_LT((some.covariance.block<2, 2>(0, 2) - all.covariance.block<2, 2>(4, 0)).norm(), 1e-15);
	EXPECT_LT((some.covariance.block<2, 2>(2, 2) - all.covariance.block<2, 2>(0, 0)).norm(), 1e-15);
}

}  // namespace
