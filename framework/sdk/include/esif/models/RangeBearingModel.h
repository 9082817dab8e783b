#pragma once
/// \file RangeBearingModel.h
/// Range-bearing observation of a point feature from a sensor mounted on the
/// robot (book eq. 1.6), its inverse (landmark initialisation) and Jacobians.

#include <esif/models/Se2.h>

#include <Eigen/Core>

namespace esif
{
/// Predicted measurement h = (range, bearing) and its Jacobians.
struct RangeBearingPrediction
{
	Eigen::Vector2d z;	///< (range [m], bearing [rad]), bearing wrapped to (-pi, pi]
	Eigen::Matrix<double, 2, 3> d_robot;  ///< dh / d(robot x, y, phi)
	Eigen::Matrix2d d_landmark;	 ///< dh / d(landmark x, y)
};

/// Eq. (1.6) with the sensor at `sensor_on_robot` in the robot frame.
RangeBearingPrediction predictRangeBearing(
	const Pose2& robot, const Pose2& sensor_on_robot, const Eigen::Vector2d& landmark);

/// Inverse model: landmark position from a measurement, and its Jacobians.
struct LandmarkFromMeasurement
{
	Eigen::Vector2d position;
	Eigen::Matrix<double, 2, 3> d_robot;  ///< d position / d(robot x, y, phi)
	Eigen::Matrix2d d_measurement;	///< d position / d(range, bearing)
};

LandmarkFromMeasurement landmarkFromRangeBearing(
	const Pose2& robot, const Pose2& sensor_on_robot, double range_m, double bearing_rad);

}  // namespace esif
