#include <NumericJacobian.h>

#include <esif/models/RangeBearingModel.h>

#include <gtest/gtest.h>

namespace
{
using namespace esif;

// A sensor mounted off-centre and rotated, so the chain rule through the
// mounting pose is exercised; the robot heading near pi exercises wrapping.
const Pose2 kRobot(2.0, -1.0, 3.0);
const Pose2 kSensor(0.4, -0.1, 0.3);
const Eigen::Vector2d kLandmark(-1.5, 0.8);

TEST(RangeBearingModel, PredictionMatchesGeometry)
{
	const auto h = predictRangeBearing(kRobot, kSensor, kLandmark);
	const Pose2 s = compose(kRobot, kSensor);
	EXPECT_NEAR(h.z(0), (kLandmark - s.head<2>()).norm(), 1e-12);
	// The measurement points back at the landmark.
	const auto back = landmarkFromRangeBearing(kRobot, kSensor, h.z(0), h.z(1));
	EXPECT_LT((back.position - kLandmark).norm(), 1e-12);
}

TEST(RangeBearingModel, JacobiansMatchFiniteDifferences)
{
	const auto h = predictRangeBearing(kRobot, kSensor, kLandmark);
	const auto num_robot = test::numericJacobian(
		[&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return predictRangeBearing(Pose2(x), kSensor, kLandmark).z; },
		kRobot, 1e-6, {1});
	const auto num_lm = test::numericJacobian(
		[&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return predictRangeBearing(kRobot, kSensor, x).z; },
		kLandmark, 1e-6, {1});
	EXPECT_LT((h.d_robot - num_robot).cwiseAbs().maxCoeff(), 1e-7);
	EXPECT_LT((h.d_landmark - num_lm).cwiseAbs().maxCoeff(), 1e-7);
}

TEST(RangeBearingModel, InverseJacobiansMatchFiniteDifferences)
{
	const double r = 3.2, b = -2.9;
	const auto g = landmarkFromRangeBearing(kRobot, kSensor, r, b);
	const auto num_robot = test::numericJacobian(
		[&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
			return landmarkFromRangeBearing(Pose2(x), kSensor, r, b).position;
		},
		kRobot);
	const auto num_z = test::numericJacobian(
		[&](const Eigen::VectorXd& z) -> Eigen::VectorXd {
			return landmarkFromRangeBearing(kRobot, kSensor, z(0), z(1)).position;
		},
		Eigen::Vector2d(r, b));
	EXPECT_LT((g.d_robot - num_robot).cwiseAbs().maxCoeff(), 1e-7);
	EXPECT_LT((g.d_measurement - num_z).cwiseAbs().maxCoeff(), 1e-7);
}

}  // namespace
