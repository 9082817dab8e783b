/// \file VelocityOdometry.cpp
/// Velocity commands integrated into a relative pose and its covariance;
/// see VelocityOdometry.h.

#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/models/VelocityOdometry.h>

#include <cmath>

namespace esif
{
namespace
{
/// `pose` after driving `v`, `w` for `h` seconds (an exact arc; a straight
/// line when the turn is below round-off).
Pose2 drive(const Pose2& pose, double v, double w, double h)
{
	const double th = pose.z();
	if (std::abs(w * h) < 1e-9) return {pose.x() + v * h * std::cos(th), pose.y() + v * h * std::sin(th), th};
	const double th1 = th + w * h;
	return {pose.x() + v / w * (std::sin(th1) - std::sin(th)), pose.y() + v / w * (std::cos(th) - std::cos(th1)), th1};
}

/// One sub-step of the integration: the command and the pose at its middle.
struct SubStep
{
	double h = 0;
	double v = 0;
	double w = 0;
	Pose2 middle;
};

/// The sub-steps of `segments` (each at most `max_h` long) and the end pose
/// (heading not wrapped).
std::vector<SubStep> subSteps(const std::vector<VelocitySegment>& segments, double max_h, Pose2& end)
{
	std::vector<SubStep> out;
	Pose2 pose = Pose2::Zero();
	for (const auto& seg : segments)
	{
		const int n = std::max(1, static_cast<int>(std::ceil(seg.duration_s / max_h)));
		const double h = seg.duration_s / n;
		for (int i = 0; i < n; ++i)
		{
			out.push_back({h, seg.v_mps, seg.w_radps, drive(pose, seg.v_mps, seg.w_radps, h / 2)});
			pose = drive(pose, seg.v_mps, seg.w_radps, h);
		}
	}
	end = pose;
	return out;
}

double floorOf(const VelocityNoise& n) { return n.floor_m; }
double speedScaleOf(const VelocityNoise& n) { return n.speed_scale; }
double turnScaleOf(const VelocityNoise& n) { return n.turn_scale; }
double speedPsdOf(const VelocityNoise& n) { return n.speed_psd; }
double turnPsdOf(const VelocityNoise& n) { return n.turn_psd; }
double turnPsdPerRateOf(const VelocityNoise& n) { return n.turn_psd_per_rate; }
}  // namespace

const std::vector<VelocityNoiseParameter>& velocityNoiseParameters()
{
	static const std::vector<VelocityNoiseParameter> params = {
		{"odometry-floor-m", "odometry: position noise of each step's end points [m]", "M", floorOf,
		 [](VelocityNoise& n, double v) { n.floor_m = v; }},
		{"odometry-speed-scale", "odometry: speed error held over a step, as a fraction of its mean speed", "F",
		 speedScaleOf, [](VelocityNoise& n, double v) { n.speed_scale = v; }},
		{"odometry-turn-scale", "odometry: turn-rate error held over a step, as a fraction of its mean turn rate", "F",
		 turnScaleOf, [](VelocityNoise& n, double v) { n.turn_scale = v; }},
		{"odometry-speed-psd", "odometry: white noise on the speed [m^2/s]", "Q", speedPsdOf,
		 [](VelocityNoise& n, double v) { n.speed_psd = v; }},
		{"odometry-turn-psd", "odometry: white noise on the turn rate [rad^2/s]", "R", turnPsdOf,
		 [](VelocityNoise& n, double v) { n.turn_psd = v; }},
		{"odometry-turn-psd-per-rate", "odometry: more turn-rate noise per rad/s of turning [rad/s per rad/s]", "R",
		 turnPsdPerRateOf, [](VelocityNoise& n, double v) { n.turn_psd_per_rate = v; }},
	};
	return params;
}

void VelocityNoise::validate(const std::string& who) const
{
	for (const auto& p : velocityNoiseParameters())
	{
		const double v = p.get(*this);
		// Beyond 1e3 no parameter describes a vehicle (a 1 km floor, a speed
		// error of 1000 times the speed).
		if (!(std::isfinite(v) && v >= 0 && v <= 1e3))
			throw ConfigError(who + ": --" + p.flag + " = " + formatNumber(v) + ": must be in [0, 1000]");
	}
	// The floor alone keeps the position variances positive and the turn-rate
	// noise the heading's (on a straight stretch nothing else adds to it);
	// below these a variance rounds to nothing next to the others, and a
	// subnormal one squares to zero: a singular covariance in the rawlog.
	if (!(floor_m >= kMinOdometryFloor_m))
		throw ConfigError(
			who + ": --odometry-floor-m = " + formatNumber(floor_m) + ": must be at least " +
			formatNumber(kMinOdometryFloor_m) + " m (the position covariance is singular otherwise)");
	if (!(turn_psd >= kMinTurnPsd))
		throw ConfigError(
			who + ": --odometry-turn-psd = " + formatNumber(turn_psd) + ": must be at least " +
			formatNumber(kMinTurnPsd) + " rad^2/s (the heading covariance of a straight step is singular otherwise)");
}

Pose2 integrateVelocity(const std::vector<VelocitySegment>& segments)
{
	Pose2 end;
	subSteps(segments, 1e9, end);
	return end;
}

OdometryIncrement velocityOdometry(
	const std::vector<VelocitySegment>& segments, const VelocityNoise& noise, double max_substep_s)
{
	Pose2 end;
	const std::vector<SubStep> steps = subSteps(segments, max_substep_s, end);
	Eigen::Vector3d j_v = Eigen::Vector3d::Zero(), j_w = Eigen::Vector3d::Zero();
	Eigen::Matrix3d random_walk = Eigen::Matrix3d::Zero();
	double duration = 0, distance = 0, turn = 0;
	for (const SubStep& s : steps)
	{
		const Eigen::Vector3d u(std::cos(s.middle.z()), std::sin(s.middle.z()), 0);
		const Eigen::Vector3d g(-(end.y() - s.middle.y()), end.x() - s.middle.x(), 1);
		j_v += s.h * u;
		j_w += s.h * g;
		random_walk += s.h * (noise.speed_psd * u * u.transpose() +
							  (noise.turn_psd + noise.turn_psd_per_rate * std::abs(s.w)) * g * g.transpose());
		duration += s.h;
		distance += s.h * s.v;
		turn += s.h * s.w;
	}
	const double v_mean = duration > 0 ? distance / duration : 0, w_mean = duration > 0 ? turn / duration : 0;
	OdometryIncrement out;
	out.delta = Pose2(end.x(), end.y(), wrapAngle(end.z()));
	out.cov = random_walk + std::pow(noise.speed_scale * v_mean, 2) * j_v * j_v.transpose() +
			  std::pow(noise.turn_scale * w_mean, 2) * j_w * j_w.transpose();
	out.cov(0, 0) += noise.floor_m * noise.floor_m;
	out.cov(1, 1) += noise.floor_m * noise.floor_m;
	out.cov = 0.5 * (out.cov + out.cov.transpose()).eval();	// (s u) u^T rounds apart from u (s u)^T
	return out;
}

}  // namespace esif
