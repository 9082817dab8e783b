#include <esif/calibration/CalibrationChecks.h>

#include <algorithm>
#include <cmath>

namespace esif
{
namespace
{
/// Odometry composed over steps [first, first + W) with its propagated
/// covariance (eq. 1.8 with the robot at the window's start); nullopt when a
/// step of the window has no odometry.
struct ComposedOdometry
{
	Pose2 delta = Pose2::Zero();
	Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
};

std::optional<ComposedOdometry> composeWindow(const std::vector<StepInput>& steps, std::size_t first, std::size_t W)
{
	ComposedOdometry out;
	for (std::size_t k = first; k < first + W; ++k)
	{
		if (!steps[k].odometry) return std::nullopt;
		const Pose2 u = steps[k].odometry->delta;
		const auto J = composeJacobians(out.delta, u);
		out.cov = J.d_a * out.cov * J.d_a.transpose() + J.d_b * steps[k].odometry->cov * J.d_b.transpose();
		out.delta = compose(out.delta, u);
	}
	return out;
}

OdometryWindowCheck windowCheck(
	const std::vector<StepInput>& steps, const std::vector<Pose2>& path, std::size_t W, std::size_t stride)
{
	OdometryWindowCheck check;
	check.steps = W;
	double heading_sq = 0;
	// Step k's odometry moves the robot from pose k-1 to pose k: a window of
	// steps [s, s + W) spans poses s-1 .. s+W-1.
	for (std::size_t s = 1; s + W <= steps.size() && s + W - 1 < path.size(); s += stride)
	{
		const auto odo = composeWindow(steps, s, W);
		if (!odo) continue;
		Pose2 error = odo->delta - inverseCompose(path[s - 1], path[s + W - 1]);
		error(2) = wrapAngle(error(2));
		check.normalised_error += error.cwiseAbs2().cwiseQuotient(odo->cov.diagonal().cwiseMax(1e-300));
		heading_sq += error(2) * error(2);
		++check.windows;
	}
	if (check.windows)
	{
		check.normalised_error /= static_cast<double>(check.windows);
		check.heading_rms_rad = std::sqrt(heading_sq / static_cast<double>(check.windows));
	}
	return check;
}
}  // namespace

std::vector<OdometryWindowCheck> odometryWindowChecks(
	const std::vector<StepInput>& steps, const std::vector<Pose2>& path, const std::vector<std::size_t>& lengths,
	bool overlapping)
{
	std::vector<OdometryWindowCheck> out;
	for (const std::size_t W : lengths)
		if (W > 0) out.push_back(windowCheck(steps, path, W, overlapping ? std::max<std::size_t>(1, W / 4) : W));
	return out;
}

void forEachSensorResidual(
	const std::vector<StepInput>& steps, const std::vector<Pose2>& path,
	const std::map<LandmarkId, Eigen::Vector2d>& landmarks,
	const std::function<void(const Scan&, const RangeBearing&, double, double)>& visit)
{
	for (std::size_t k = 0; k < steps.size() && k < path.size(); ++k)
	{
		if (!steps[k].scan) continue;
		const Scan& scan = *steps[k].scan;
		const Pose2 sensor = compose(path[k], scan.sensor_on_robot);
		for (const auto& m : scan.measurements)
		{
			const auto it = m.id ? landmarks.find(*m.id) : landmarks.end();
			if (it == landmarks.end()) continue;
			const Eigen::Vector2d d = it->second - sensor.head<2>();
			visit(scan, m, m.range_m - d.norm(), wrapAngle(m.bearing_rad - std::atan2(d.y(), d.x()) + sensor(2)));
		}
	}
}

namespace
{
/// Normalised residuals (range, bearing) of every measurement, per landmark in step order.
std::map<LandmarkId, std::vector<Eigen::Vector2d>> normalisedResidualsByLandmark(
	const std::vector<StepInput>& steps, const std::vector<Pose2>& path,
	const std::map<LandmarkId, Eigen::Vector2d>& landmarks)
{
	std::map<LandmarkId, std::vector<Eigen::Vector2d>> out;
	forEachSensorResidual(steps, path, landmarks, [&](const Scan&, const RangeBearing& m, double range, double bearing) {
		out[*m.id].emplace_back(range / std::sqrt(m.cov(0, 0)), bearing / std::sqrt(m.cov(1, 1)));
	});
	return out;
}
}  // namespace

std::vector<SensorWindowCheck> sensorWindowChecks(
	const std::vector<StepInput>& steps, const std::vector<Pose2>& path,
	const std::map<LandmarkId, Eigen::Vector2d>& landmarks, const std::vector<std::size_t>& lengths,
	double outlier_sigmas)
{
	auto residuals = normalisedResidualsByLandmark(steps, path, landmarks);
	for (auto& [id, r] : residuals)
		r.erase(std::remove_if(r.begin(), r.end(), [&](const Eigen::Vector2d& e) { return e.cwiseAbs().maxCoeff() > outlier_sigmas; }),
				r.end());
	std::vector<SensorWindowCheck> out;
	for (const std::size_t W : lengths)
	{
		SensorWindowCheck c;
		c.measurements = W;
		for (const auto& [id, r] : residuals)
			for (std::size_t s = 0; W > 0 && s + W <= r.size(); s += W)
			{
				Eigen::Vector2d sum = Eigen::Vector2d::Zero();
				for (std::size_t i = s; i < s + W; ++i) sum += r[i];
				c.range_normalised += sum(0) * sum(0) / static_cast<double>(W);
				c.bearing_normalised += sum(1) * sum(1) / static_cast<double>(W);
				++c.windows;
			}
		if (c.windows)
		{
			c.range_normalised /= static_cast<double>(c.windows);
			c.bearing_normalised /= static_cast<double>(c.windows);
		}
		out.push_back(c);
	}
	return out;
}

SensorResidualCheck sensorResidualCheck(
	const std::vector<StepInput>& steps, const std::vector<Pose2>& path,
	const std::map<LandmarkId, Eigen::Vector2d>& landmarks)
{
	SensorResidualCheck c;
	forEachSensorResidual(steps, path, landmarks, [&](const Scan&, const RangeBearing& m, double range, double bearing) {
		c.range_mean_m += range;
		c.range_rms_m += range * range;
		c.bearing_mean_rad += bearing;
		c.bearing_rms_rad += bearing * bearing;
		c.range_normalised += range * range / m.cov(0, 0);
		c.bearing_normalised += bearing * bearing / m.cov(1, 1);
		++c.measurements;
	});
	if (c.measurements == 0) return c;
	const double n = static_cast<double>(c.measurements);
	c.range_mean_m /= n;
	c.bearing_mean_rad /= n;
	c.range_rms_m = std::sqrt(c.range_rms_m / n);
	c.bearing_rms_rad = std::sqrt(c.bearing_rms_rad / n);
	c.range_normalised /= n;
	c.bearing_normalised /= n;
	return c;
}

}  // namespace esif
