#pragma once
/// \file VelocityOdometry.h
/// Odometry from velocity commands (a unicycle driven by commanded forward
/// speed and turn rate, as the UTIAS MRCLAM robots log it): the relative pose
/// reached by a sequence of commands, integrated exactly arc by arc, and a
/// velocity-model covariance of it in the frame of the start pose.
///
/// The covariance is a hybrid of two error kinds, each measured against
/// Vicon on MRCLAM dataset 6 (8,812 intervals of 1 ms to 78 s, all five
/// robots): a speed and turn-rate error held constant over the interval (a
/// scale error of the commands: b_v |v_mean|, b_w |w_mean|), plus white
/// noise on the speed and turn rate that accumulates as a random walk (q_v;
/// r0 + r1 |w|), plus a position floor s for the interval's end points. With
///   u(s) = (cos th_s, sin th_s, 0) and g(s) = (-(y_k - y_s), x_k - x_s, 1)
/// (the effect at the interval's end pose k of a unit speed or turn-rate
/// impulse at time s along the integrated path),
///   Sigma = diag(s^2, s^2, 0) + (b_v v_mean)^2 J_v J_v^T + (b_w w_mean)^2 J_w J_w^T
///         + int [ q_v u u^T + (r0 + r1 |w(s)|) g g^T ] ds,
/// with J_v = int u ds and J_w = int g ds. Neither error kind alone is
/// consistent beyond a few seconds (the mean NEES of 10-78 s blind drives
/// is 14-71 with one of them, 2.3 with both); see docs of `esif import mrclam`.

#include <esif/core/StepInput.h>
#include <esif/models/Se2.h>

#include <string>
#include <vector>

namespace esif
{
/// A command (forward speed, turn rate) held for `duration_s`.
struct VelocitySegment
{
	double duration_s = 0;
	double v_mps = 0;
	double w_radps = 0;
};

/// The velocity model's parameters (see the file comment). Defaults: the
/// maximum-likelihood fit on MRCLAM dataset 6, all five robots pooled.
struct VelocityNoise
{
	double floor_m = 0.00083;	 ///< s: position noise of the interval's end points
	double speed_scale = 0.141;	 ///< b_v: constant speed error, as a fraction of |v_mean|
	double turn_scale = 0.217;	///< b_w: constant turn-rate error, as a fraction of |w_mean|
	double speed_psd = 2.96e-5;	 ///< q_v [m^2/s]: white noise on the speed
	double turn_psd = 3.03e-4;	///< r0 [rad^2/s]: white noise on the turn rate
	double turn_psd_per_rate = 0.0176;	///< r1 [rad/s per rad/s]: more of it while turning

	/// Throws ConfigError "`who`: --FLAG = V: ..." unless every value is
	/// finite and non-negative, the floor at least kMinOdometryFloor_m and
	/// the turn-rate noise at least kMinTurnPsd, so that no step's
	/// covariance is singular.
	void validate(const std::string& who) const;
};

/// Smallest odometry floor [m]: a micrometre; its square still adds to the
/// position variance of a step (a subnormal floor squares to zero).
inline constexpr double kMinOdometryFloor_m = 1e-6;
/// Smallest white turn-rate noise [rad^2/s]: on a straight step it is all
/// of the heading's variance.
inline constexpr double kMinTurnPsd = 1e-12;

/// One parameter of VelocityNoise, for command lines and listings.
struct VelocityNoiseParameter
{
	const char* flag;  ///< command-line name, e.g. "odometry-speed-scale"
	const char* help;
	const char* unit;
	double (*get)(const VelocityNoise&);
	void (*set)(VelocityNoise&, double);
};
const std::vector<VelocityNoiseParameter>& velocityNoiseParameters();

/// The pose reached from the origin by driving `segments` (exact arcs).
Pose2 integrateVelocity(const std::vector<VelocitySegment>& segments);

/// The increment and its covariance (file comment) of driving `segments`.
/// The integrals are taken over sub-steps of at most `max_substep_s`.
OdometryIncrement velocityOdometry(
	const std::vector<VelocitySegment>& segments, const VelocityNoise& noise, double max_substep_s = 0.02);

}  // namespace esif
