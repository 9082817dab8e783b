#pragma once
/// \file StepInput.h
/// The neutral input a filter plugin receives for one rawlog step. The host
/// builds it from MRPT rawlog entries; plugins never see rawlog classes, so
/// they can be driven by hand-made inputs in tests.

#include <esif/core/Pose2.h>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace esif
{
/// Identity of a landmark as carried by the sensor (e.g. a beacon ID) or as
/// assigned by a filter for a landmark it created itself.
using LandmarkId = std::int64_t;

/// Odometry increment: pose k in the frame of pose k-1, with its 3x3
/// covariance over (dx [m], dy [m], dphi [rad]).
struct OdometryIncrement
{
	Pose2 delta = Pose2::Zero();  ///< (dx, dy, dphi); (2) = heading change
	Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
};

/// True for the odometry of a step that does not move the robot: a zero
/// increment with a zero covariance (e.g. the first step of an imported
/// log). The full-SLAM problem adds no pose for it: a constraint with zero
/// covariance cannot be whitened.
inline bool isStandStill(const OdometryIncrement& odometry)
{
	return odometry.cov.isZero(0) && odometry.delta.isZero(0);
}

/// One range-bearing measurement of a point feature, in the sensor frame.
struct RangeBearing
{
	double range_m = 0;
	double bearing_rad = 0;	 ///< in (-pi, pi], counter-clockwise from the sensor's x axis
	/// Covariance of (range [m], bearing [rad]): what an estimator fuses.
	Eigen::Matrix2d cov = Eigen::Matrix2d::Identity();
	/// Landmark identity when the sensor provides it (known data association).
	std::optional<LandmarkId> id;
};

/// All range-bearing measurements taken at one robot pose.
struct Scan
{
	Pose2 sensor_on_robot = Pose2::Zero();	///< sensor pose in the robot frame
	double max_range_m = 0;	 ///< 0 when unknown/unlimited
	double fov_rad = 0;	 ///< full field of view; 0 when unknown
	std::vector<RangeBearing> measurements;
	/// Covariance of one measurement alone, when it differs from each
	/// measurement's `cov`: what an association test compares an innovation
	/// against (sightingCov()). A calibration sets it when errors repeat over
	/// the sightings of one landmark: `cov` is then inflated so that sums of
	/// sightings fuse consistently, and would widen every gate by the same
	/// factor. One per scan, the sensor's: a long log holds millions of
	/// measurements.
	std::optional<Eigen::Matrix2d> sighting_cov;
};

/// The noise of one sighting of `m`, a measurement of `scan`: the scan's
/// sighting_cov when set, otherwise the measurement's own.
inline const Eigen::Matrix2d& sightingCov(const Scan& scan, const RangeBearing& m)
{
	return scan.sighting_cov ? *scan.sighting_cov : m.cov;
}

/// One step of a replay: an odometry increment (if any) followed by the
/// measurements taken at the new pose (if any).
struct StepInput
{
	std::size_t index = 0;	///< 0-based step index in the rawlog
	double time_s = 0;	///< timestamp [s]; the step index when the log has none
	std::optional<OdometryIncrement> odometry;
	std::optional<Scan> scan;
};

}  // namespace esif
