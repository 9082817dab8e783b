#pragma once
/// \file EkfCoreFixture.h
/// A small EKF core with a correlated covariance, shared by the core's tests.

#include <esif/ekf/EkfSlamCore.h>

namespace esif::test
{
inline const Pose2 kSensor(0.2, 0.05, 0.1);

/// A robot that drives three steps with odometry noise and maps three
/// landmarks: (3.0 m, 0.4 rad) after the first step, (2.0 m, -0.7 rad) and
/// `third` (range, bearing) after the second.
inline EkfSlamCore coreWithThreeLandmarks(const Eigen::Vector2d& third = {4.0, 1.2})
{
	EkfSlamCore core;
	OdometryIncrement u;
	u.delta = {0.5, 0.1, 0.2};
	u.cov = Eigen::Vector3d(0.01, 0.02, 0.003).asDiagonal();
	const Eigen::Matrix2d R = Eigen::Vector2d(0.01, 0.0004).asDiagonal();
	core.predict(u);
	core.addLandmark({3.0, 0.4}, R, kSensor);
	core.predict(u);
	core.addLandmark({2.0, -0.7}, R, kSensor);
	core.addLandmark(third, R, kSensor);
	core.predict(u);
	return core;
}

}  // namespace esif::test
