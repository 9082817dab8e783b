#include <esif/models/RangeBearingModel.h>

#include <cmath>

namespace esif
{
RangeBearingPrediction predictRangeBearing(
	const Pose2& robot, const Pose2& sensor_on_robot, const Eigen::Vector2d& landmark)
{
	// Sensor pose in the world: s = robot (+) sensor_on_robot.
	const Pose2 sensor = compose(robot, sensor_on_robot);
	const double dx = landmark.x() - sensor.x(), dy = landmark.y() - sensor.y();
	const double q = dx * dx + dy * dy;
	const double r = std::sqrt(q);

	RangeBearingPrediction out;
	// Eq. (1.6): r = |l - s|, theta = atan2(dy, dx) - phi_s.
	out.z = {r, wrapAngle(std::atan2(dy, dx) - sensor.z())};

	// d(r, theta)/d(sensor x, y, phi) and d/d(landmark).
	Eigen::Matrix<double, 2, 3> d_sensor;
	d_sensor << -dx / r, -dy / r, 0,  //
		dy / q, -dx / q, -1;
	out.d_landmark << dx / r, dy / r,  //
		-dy / q, dx / q;
	// Chain rule through the composition robot (+) sensor_on_robot.
	out.d_robot = d_sensor * composeJacobians(robot, sensor_on_robot).d_a;
	return out;
}

LandmarkFromMeasurement landmarkFromRangeBearing(
	const Pose2& robot, const Pose2& sensor_on_robot, double range_m, double bearing_rad)
{
	const Pose2 sensor = compose(robot, sensor_on_robot);
	const double angle = sensor.z() + bearing_rad;
	const double c = std::cos(angle), s = std::sin(angle);

	LandmarkFromMeasurement out;
	out.position = {sensor.x() + range_m * c, sensor.y() + range_m * s};

	Eigen::Matrix<double, 2, 3> d_sensor;
	d_sensor << 1, 0, -range_m * s,	 //
		0, 1, range_m * c;
	out.d_robot = d_sensor * composeJacobians(robot, sensor_on_robot).d_a;
	out.d_measurement << c, -range_m * s,  //
		s, range_m * c;
	return out;
}

}  // namespace esif
