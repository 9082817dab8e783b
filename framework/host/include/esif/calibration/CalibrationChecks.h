#pragma once
/// \file CalibrationChecks.h
/// How well a noise model describes a rawlog against a reference trajectory
/// and map (ground truth, or a full-SLAM run): the checks `esif calibrate`
/// prints beside its fit.
///
/// Odometry is checked on windows of W consecutive steps, not only on one:
/// the increments of a window composed, their covariances propagated
/// (eq. 1.8), and the error against the reference's relative pose
/// normalised per component. White noise gives a normalised squared error
/// of 1 at every W; an error that behaves like a bias (a miscalibrated
/// wheel, a heading drift) grows with W, which a one-step check cannot see.

#include <esif/core/StepInput.h>
#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <functional>
#include <map>
#include <vector>

namespace esif
{
struct OdometryWindowCheck
{
	std::size_t steps = 0;	///< W
	std::size_t windows = 0;  ///< non-overlapping windows compared
	/// Mean squared error over variance of x, y (window frame) and heading: 1 when consistent.
	Eigen::Vector3d normalised_error = Eigen::Vector3d::Zero();
	/// RMS heading error over the windows [rad].
	double heading_rms_rad = 0;
};

/// The windows of each length in `lengths` over `steps` (calibrated as the
/// filter would see them) against `path` (one reference pose per step).
/// Windows that cross a step without odometry, or pass the path's end, are
/// left out. `overlapping`: a window of W steps starts every max(1, W/4)
/// steps instead of every W (four times the windows, for a fit; their
/// errors are correlated, the mean stays unbiased).
std::vector<OdometryWindowCheck> odometryWindowChecks(
	const std::vector<StepInput>& steps, const std::vector<Pose2>& path, const std::vector<std::size_t>& lengths,
	bool overlapping = false);

struct SensorResidualCheck
{
	std::size_t measurements = 0;  ///< with a reference pose and landmark
	double range_mean_m = 0, range_rms_m = 0;
	double bearing_mean_rad = 0, bearing_rms_rad = 0;
	/// Mean of (residual / modelled sigma)^2 per component: 1 when the noise
	/// is right (against ground truth; against a fitted optimum smaller,
	/// its residuals being shrunk by the fit).
	double range_normalised = 0, bearing_normalised = 0;
};

/// Calls `visit(scan, measurement, range error [m], bearing error [rad])`
/// for every measurement with an ID whose step has a reference pose and
/// whose ID a reference landmark: the measurement minus eq. (1.6) at the
/// reference (bearing wrapped). The one residual of every sensor check and fit.
void forEachSensorResidual(
	const std::vector<StepInput>& steps, const std::vector<Pose2>& path,
	const std::map<LandmarkId, Eigen::Vector2d>& landmarks,
	const std::function<void(const Scan&, const RangeBearing&, double, double)>& visit);

/// Every measurement with an ID against the reference pose of its step and
/// the reference landmark of its ID.
SensorResidualCheck sensorResidualCheck(
	const std::vector<StepInput>& steps, const std::vector<Pose2>& path,
	const std::map<LandmarkId, Eigen::Vector2d>& landmarks);

/// The sensor's counterpart of the odometry windows: W consecutive
/// measurements of one landmark, their residuals summed and normalised by
/// W sigma^2 per component. 1 at every W when the errors are independent;
/// growing with W when each landmark (or each viewpoint) has an error of
/// its own, which a filter averaging many sightings cannot see, so its map
/// becomes over-confident however right the one-measurement noise is.
struct SensorWindowCheck
{
	std::size_t measurements = 0;  ///< W
	std::size_t windows = 0;
	double range_normalised = 0, bearing_normalised = 0;
};

/// Residuals beyond `outlier_sigmas` of either component are left out.
std::vector<SensorWindowCheck> sensorWindowChecks(
	const std::vector<StepInput>& steps, const std::vector<Pose2>& path,
	const std::map<LandmarkId, Eigen::Vector2d>& landmarks, const std::vector<std::size_t>& lengths,
	double outlier_sigmas = 5);

}  // namespace esif
