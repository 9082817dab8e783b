#pragma once
/// \file FullSlamProblem.h
/// The full-SLAM problem of a rawlog (book Sec. 1.2.2.2, eq. 1.18-1.21) as
/// plain data, for solvers outside esif (g2o, GTSAM): every robot pose and
/// every landmark an unknown with an initial value, every odometry increment
/// a pose-pose factor and every range-bearing measurement with a landmark ID
/// a pose-landmark factor, each with its covariance.
///
/// Poses are made as the ceres_full plugin makes them, so that the two
/// problems are the same: pose 0 is the initial robot pose, the origin of
/// the map frame (the gauge); each step whose odometry is not a stand-still
/// (zero increment with zero covariance, e.g. step 0 of a simulated rawlog)
/// adds a pose; a step's measurements are taken at the pose current after
/// its odometry.

#include <esif/core/StepInput.h>
#include <esif/formats/RawlogReader.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace esif
{
/// Odometry factor (eq. 1.19): pose `to` = pose `from` (+) delta, delta ~ N(., cov).
struct OdometryFactor
{
	std::size_t step = 0;  ///< rawlog step of the increment
	std::size_t from = 0;
	std::size_t to = 0;
	Pose2 delta = Pose2::Zero();  ///< (dx [m], dy [m], dphi [rad]) in the frame of pose `from`
	Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
};

/// Range-bearing factor (eq. 1.20 with the model of eq. 1.6).
struct RangeBearingFactor
{
	std::size_t step = 0;  ///< rawlog step of the scan
	std::size_t measurement = 0;  ///< index in the step's scan
	std::size_t pose = 0;
	LandmarkId landmark = 0;
	double range_m = 0;
	double bearing_rad = 0;
	Eigen::Matrix2d cov = Eigen::Matrix2d::Identity();	///< of (range [m], bearing [rad])
	Pose2 sensor_on_robot = Pose2::Zero();
};

struct FullSlamProblem
{
	/// Initial values of the poses; poses[0] is the origin.
	std::vector<Pose2> poses;
	/// Initial values of the landmarks, by ID.
	std::map<LandmarkId, Eigen::Vector2d> landmarks;
	std::vector<OdometryFactor> odometry;
	std::vector<RangeBearingFactor> observations;
	/// The pose current after each rawlog step, and the step's timestamp (as
	/// trajectory.tum writes it).
	std::vector<std::size_t> step_pose;
	std::vector<double> step_time_s;
	/// Measurements left out because they carry no landmark ID (rejected by
	/// the run whose associations were applied).
	std::size_t measurements_without_id = 0;
};


/// Builds the problem of `log` (landmark IDs as `log` carries them: apply a
/// run's associations first when it has none). Initial values: with
/// `initial`, another run's pose after the step that made each pose and its
/// landmark positions (a landmark it did not map, or mapped as non-finite,
/// starts at its first sighting); without, dead reckoning and first
/// sightings. `initial_source` names the run folder in errors. Throws
/// InputError naming the step when an odometry covariance is not symmetric
/// positive definite, a measurement covariance is not, or `initial` has
/// fewer poses than the rawlog has steps.
FullSlamProblem buildFullSlamProblem(
	const Rawlog& log, const RunOutputs* initial = nullptr, const std::string& initial_source = "");

}  // namespace esif
