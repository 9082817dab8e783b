#pragma once
/// \file RawlogReader.h
/// Turns an MRPT rawlog (actions/sensory-frames or observations-only, gz or
/// plain) into neutral StepInputs. One step = the odometry since the previous
/// step followed by the range-bearing scan taken at the new pose:
/// - CActionRobotMovement2D (mean + Gaussian covariance) or CObservationOdometry
///   (absolute readings: the increment is the difference of two readings, its
///   covariance comes from RawlogReadOptions) start a step;
/// - CObservationBearingRange completes it. A scan with no odometry before it
///   (e.g. the first sensory frame of simul-landmarks logs) is a step with no
///   odometry; odometry with no scan after it is an odometry-only step.

#include <esif/core/StepInput.h>

#include <mrpt/obs/CSensoryFrame.h>

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
struct RawlogReadOptions
{
	/// Covariance per step of CObservationOdometry increments, which carry none:
	/// 1-sigma of x and y [m] and of phi [rad].
	double odometry_obs_std_xy_m = 0.05;
	double odometry_obs_std_phi_rad = 0.02;
	/// Sensor noise overriding the rawlog's (1-sigma range [m] and bearing
	/// [rad]); used when both are > 0, else each observation's own values.
	double sensor_std_range_m = 0;
	double sensor_std_bearing_rad = 0;
	/// Strip landmark IDs from the plugin's input (they are still kept in
	/// Rawlog::true_ids for scoring data association).
	bool hide_landmark_ids = false;
};

struct Rawlog
{
	std::string path;
	std::vector<StepInput> steps;
	/// The sensory frame behind each step (null for odometry-only steps), for maps.
	std::vector<mrpt::obs::CSensoryFrame::Ptr> frames;
	/// Landmark IDs of each step's measurements as stored in the file.
	std::vector<std::vector<std::optional<LandmarkId>>> true_ids;
	/// Set when the file ended inside an entry: says where reading stopped.
	std::optional<std::string> truncation_warning;
	std::size_t measurement_count = 0;
	bool has_odometry = false;
};

/// Reads a whole rawlog. Throws InputError (naming the file, and the entry
/// where relevant) when the file is missing, unreadable, not a rawlog, holds
/// no odometry or no bearing-range observation, or holds a non-finite or
/// negative range. A file cut inside an entry is read up to its last complete
/// step and `truncation_warning` says where it stopped.
Rawlog readRawlog(const std::string& path, const RawlogReadOptions& options = {});

}  // namespace esif
