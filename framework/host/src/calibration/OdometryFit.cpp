#include "NoiseFitParts.h"

#include <esif/core/Errors.h>

#include <Eigen/Eigenvalues>
#include <boost/math/distributions/fisher_f.hpp>
#include <optional>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace esif::noise_fit
{
namespace
{
double forwardDistance(const Pose2& d) { return std::hypot(d.x(), d.y()) * (d.x() < 0 ? -1 : 1); }

/// The window lengths checked: 1, 2, 4, ... up to `horizon`, and `horizon`.
std::vector<std::size_t> lengthsUpTo(std::size_t horizon)
{
	std::vector<std::size_t> out;
	for (std::size_t w = 1; w < horizon; w *= 2) out.push_back(w);
	out.push_back(std::max<std::size_t>(horizon, 1));
	return out;
}
}  // namespace

namespace
{
/// One window's heading: the sums of turns and of forward distances of its
/// odometry, and the reference's heading change (summed step by step, so
/// that a window turning past 180 deg is not wrapped).
struct HeadingWindow
{
	Eigen::Vector2d odometry = Eigen::Vector2d::Zero();
	double reference_turn = 0;
};

std::vector<HeadingWindow> headingWindows(const std::vector<ReferencedLog>& logs, std::size_t window,
										  double& odometry_length, double& reference_length)
{
	std::vector<HeadingWindow> out;
	for (const auto& ref : logs)
	{
		const auto& steps = ref.log.steps;
		for (std::size_t s = 1; s + window <= steps.size() && s + window - 1 < ref.path.size(); s += window)
		{
			HeadingWindow w;
			bool whole = true;
			double odo = 0, truth = 0;
			for (std::size_t k = s; k < s + window && whole; ++k)
			{
				whole = steps[k].odometry.has_value();
				if (!whole) break;
				const auto& d = steps[k].odometry->delta;
				w.odometry += Eigen::Vector2d(d(2), forwardDistance(d));  // (2) = heading
				w.reference_turn += wrapAngle(ref.path[k](2) - ref.path[k - 1](2));
				odo += std::hypot(d.x(), d.y());
				truth += (ref.path[k].head<2>() - ref.path[k - 1].head<2>()).norm();
			}
			if (!whole) continue;
			out.push_back(w);
			odometry_length += odo;
			reference_length += truth;
		}
	}
	return out;
}

/// Least squares of turn_scale * turns + drift * distance = reference turn
/// over the windows of one parity (every other window); nullopt when they
/// cannot tell the two apart (no turning, or turns and distance in lockstep).
std::optional<Eigen::Vector2d> headingFit(const std::vector<HeadingWindow>& windows, std::size_t parity)
{
	Eigen::Matrix2d AtA = Eigen::Matrix2d::Zero();
	Eigen::Vector2d Atb = Eigen::Vector2d::Zero();
	for (std::size_t i = parity; i < windows.size(); i += 2)
		AtA += windows[i].odometry * windows[i].odometry.transpose(), Atb += windows[i].odometry * windows[i].reference_turn;
	const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(AtA);
	if (eig.eigenvalues()(0) <= 1e-9 * std::max(eig.eigenvalues()(1), 1e-300)) return std::nullopt;
	return AtA.ldlt().solve(Atb);
}

/// Squared heading error of the windows of one parity under (turn scale, drift).
double headingError(const std::vector<HeadingWindow>& windows, std::size_t parity, const Eigen::Vector2d& x)
{
	double sum = 0;
	for (std::size_t i = parity; i < windows.size(); i += 2)
		sum += std::pow(windows[i].odometry.dot(x) - windows[i].reference_turn, 2);
	return sum;
}

/// Whether the two-parameter correction lowers the squared error of all
/// windows by more than chance would at the 0.99 level (F test of nested
/// least squares: F = ((SSE0 - SSE1) / 2) / (SSE1 / (n - 2)) against F(2, n - 2)).
bool significant(const std::vector<HeadingWindow>& windows, const Eigen::Vector2d& x)
{
	const double n = static_cast<double>(windows.size());
	if (n < 10) return false;
	const double sse0 = headingError(windows, 0, Eigen::Vector2d(1, 0)) + headingError(windows, 1, Eigen::Vector2d(1, 0));
	const double sse1 = headingError(windows, 0, x) + headingError(windows, 1, x);
	if (sse1 <= 0) return sse0 > 0;
	const double F = ((sse0 - sse1) / 2) / (sse1 / (n - 2));
	return F > boost::math::quantile(boost::math::fisher_f_distribution<double>(2, n - 2), 0.99);
}
}  // namespace

bool fitOdometryBias(const std::vector<ReferencedLog>& logs, std::size_t window, NoiseCalibration& calibration)
{
	double odometry_length = 0, reference_length = 0;
	const auto windows = headingWindows(logs, window, odometry_length, reference_length);
	// Two tests before a systematic correction is believed. Held out: the
	// correction fitted on the even windows must lower the error of the odd
	// ones and the other way round, or the data do not show a systematic
	// error the model can hold (turns and distances in lockstep, an error
	// that changes along the log). Significance: on all windows, a gain
	// larger than fitting two parameters to pure noise gives (F test).
	const Eigen::Vector2d none(1, 0);
	for (std::size_t parity : {0, 1})
	{
		const auto x = headingFit(windows, parity);
		if (!x || headingError(windows, 1 - parity, *x) >= headingError(windows, 1 - parity, none)) return false;
	}
	const Eigen::Vector2d x = *headingFit(windows, 0) * 0.5 + *headingFit(windows, 1) * 0.5;
	if (!significant(windows, x)) return false;
	calibration.odometry_turn_scale = x(0);
	calibration.odometry_heading_drift_deg_per_m = x(1) * kDegPerRad;
	calibration.odometry_distance_scale = odometry_length > 0 ? reference_length / odometry_length : 1;
	return true;
}

/// Window lengths with fewer windows do not enter the fit: the scale from
/// n windows has a relative standard deviation of about 1/sqrt(2n), 16% at 20.
constexpr std::size_t kMinWindows = 20;

void fitOdometryNoise(const std::vector<ReferencedLog>& logs, std::size_t horizon, NoiseCalibration& calibration)
{
	const auto lengths = lengthsUpTo(horizon);
	// Fixed point: the heading noise spreads into x-y over a window, so the
	// x-y ratio depends on the heading scale; a few passes settle it.
	for (int pass = 0; pass < 6; ++pass)
	{
		double worst_xy = 0, worst_phi = 0;
		for (const auto& ref : logs)
		{
			auto steps = ref.log.steps;
			applyNoiseCalibration(steps, calibration);
			for (const auto& check : odometryWindowChecks(steps, ref.path, lengths, /*overlapping=*/true))
			{
				// A mean over fewer windows is too noisy to take the largest of.
				if (check.windows < kMinWindows) continue;
				worst_xy = std::max(worst_xy, 0.5 * (check.normalised_error(0) + check.normalised_error(1)));
				worst_phi = std::max(worst_phi, check.normalised_error(2));
			}
		}
		if (worst_xy <= 0 || worst_phi <= 0) throw InputError("esif calibrate: no odometry window to fit the odometry noise on");
		calibration.odometry_std_scale_xy = std::clamp(calibration.odometry_std_scale_xy * std::sqrt(worst_xy), 1e-3, 1e3);
		calibration.odometry_std_scale_phi = std::clamp(calibration.odometry_std_scale_phi * std::sqrt(worst_phi), 1e-3, 1e3);
		if (std::abs(worst_xy - 1) < 0.01 && std::abs(worst_phi - 1) < 0.01) break;
	}
}

}  // namespace esif::noise_fit
