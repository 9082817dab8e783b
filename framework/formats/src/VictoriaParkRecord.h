#pragma once
/// \file VictoriaParkRecord.h
/// One line of the Victoria Park text file, parsed and checked at the border
/// (VictoriaParkImporter.cpp then only orders the records into steps): every
/// field a finite number of plausible magnitude, node IDs non-negative
/// integers, covariances positive definite. A bad field is an InputError
/// "FILE:LINE: RECORD FIELD = VALUE: rule". The file has no timestamps, so
/// there is no time order to check; the pose order is the importer's.

#include <Eigen/Core>

#include <cmath>
#include <optional>
#include <string>
#include <variant>

namespace esif::victoria_park
{
/// `ODOMETRY i j dx dy dtheta c11 c12 c13 c22 c23 c33`: pose j relative to
/// pose i, in the robot frame of i.
struct OdometryRecord
{
	long from = 0;
	long to = 0;
	Eigen::Vector3d delta = Eigen::Vector3d::Zero();  ///< dx [m], dy [m], dtheta [rad] (as in the file)
	Eigen::Matrix3d cov = Eigen::Matrix3d::Identity();
};

/// `LANDMARK i l x y c11 c12 c22`: landmark l seen from pose i as a point
/// (x forward, y left) in the robot frame of i.
struct LandmarkRecord
{
	long pose = 0;
	long landmark = 0;
	Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< [m]
	Eigen::Matrix2d cov = Eigen::Matrix2d::Identity();
};

using Record = std::variant<OdometryRecord, LandmarkRecord>;

/// The record on `line` (nullopt for a blank line); `where` is "FILE:LINE",
/// the start of every error message.
std::optional<Record> parseRecord(const std::string& line, const std::string& where);

// ---- plausibility bounds. The dataset's own extremes are far inside them
// (longest odometry step 1.47 m, largest heading change 0.13 rad, trees at
// 4.6-20.7 m, variances 4e-6 to 0.4), so a value beyond is a corrupt or
// mis-scaled file (e.g. degrees for radians), not another vehicle.

/// Longest odometry step [m]: the vehicle drives below 10 m/s, and even
/// with a pose every 10 s a step stays below 100 m.
constexpr double kMaxOdometryStep_m = 100.0;
/// Largest heading change of one step [rad]: beyond a full turn the angle is
/// not a relative heading in radians (degrees, most likely).
constexpr double kMaxHeadingChange_rad = 2 * M_PI;
/// Farthest landmark [m]: ten times the 80 m range of the SICK LMS laser
/// the trees were extracted from.
constexpr double kMaxLandmarkRange_m = 1000.0;
/// Nearest landmark [m]: at the sensor itself the bearing is undefined and
/// the measurement Jacobian (1 / range) blows up.
constexpr double kMinLandmarkRange_m = 1e-3;
/// Variance bounds (eigenvalues of every covariance) [m^2, rad^2]: below
/// 1e-12 the information (its inverse, 1e12) swamps the double-precision sum
/// with the dataset's 1e4 entries; above 1e6 (1 km standard deviation) the
/// record carries no information a filter could use.
constexpr double kMinVariance = 1e-12;
constexpr double kMaxVariance = 1e6;
/// Largest node ID: MRPT's rawlog stores landmark IDs as int32
/// (CObservationBearingRange's landmarkID).
constexpr double kMaxNodeId = 2147483647.0;

}  // namespace esif::victoria_park
