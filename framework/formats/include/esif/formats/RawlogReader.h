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
#include <cstdint>
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
	/// A scan with more measurements is refused: every filter's cost grows
	/// with it (the EKF's quadratically), and no landmark detector returns
	/// thousands per scan; a larger count is a corrupt or hostile file.
	std::size_t max_measurements_per_scan = 1000;
	/// Keep every step's MRPT sensory frame (Rawlog::frames). Without them
	/// the frames are null, and a map writer reads the ones it needs again
	/// from the file (RawlogFrames.h): on a long log they are most of what
	/// reading it holds.
	bool keep_frames = true;
	/// Keep every step (Rawlog::steps). Without them `steps` and `frames`
	/// stay empty and a replay reads the steps again from the file, one at a
	/// time (RawlogSteps.h): on a log longer than the estimate is large, the
	/// steps are most of what a run would hold. Reading from memory keeps
	/// them whatever this says (there is no file to read again).
	bool keep_steps = true;
};

/// What tells one state of a file from another without reading it: a file
/// replaced or rewritten since it was read differs in one of these.
struct FileIdentity
{
	std::uintmax_t device = 0, inode = 0, size = 0;
	std::int64_t modified_ns = 0;
	bool operator==(const FileIdentity& o) const
	{
		return device == o.device && inode == o.inode && size == o.size && modified_ns == o.modified_ns;
	}
};

/// The identity of `path` now; InputError naming it when it cannot be read.
FileIdentity identityOf(const std::string& path);

/// Where a Rawlog's steps came from, so that the file can be read again for
/// what was not kept (RawlogFrames.h): the file as it was when read, the
/// options it was read with, and a checksum of the steps it gave.
struct RawlogSource
{
	std::string path;
	FileIdentity identity;
	RawlogReadOptions options;
	std::size_t steps = 0;
	std::uint32_t steps_digest = 0;
	/// The file's timestamps were unusable (missing, or not strictly
	/// increasing): each step's time is its index.
	bool times_are_indices = false;
};

struct Rawlog
{
	std::string path;
	std::vector<StepInput> steps;
	/// The sensory frame behind each step (null for odometry-only steps, and
	/// for every step when RawlogReadOptions::keep_frames is off), for maps.
	std::vector<mrpt::obs::CSensoryFrame::Ptr> frames;
	/// Landmark IDs of each step's measurements as stored in the file.
	std::vector<std::vector<std::optional<LandmarkId>>> true_ids;
	/// Set when the file ended inside an entry: says where reading stopped.
	std::optional<std::string> truncation_warning;
	std::size_t measurement_count = 0;
	bool has_odometry = false;
	/// Whether any measurement reaches the plugins with a landmark ID (after
	/// RawlogReadOptions::hide_landmark_ids).
	bool any_landmark_id = false;
	/// The file it was read from (none when read from memory).
	std::optional<RawlogSource> source;

	/// Steps in the log, kept or not (RawlogReadOptions::keep_steps).
	std::size_t stepCount() const { return steps.empty() && source ? source->steps : steps.size(); }
	/// Whether the steps were left in the file, to be read again (RawlogSteps.h).
	bool stepsLeftInFile() const { return steps.empty() && source && source->steps > 0; }
};

/// Reads a whole rawlog. Throws InputError (one line naming the file, and the
/// entry where relevant) when the file is missing, empty, not a rawlog, fails
/// its gzip checks, holds a corrupt entry, holds no odometry or no
/// bearing-range observation, or holds an invalid value (see the checks in
/// RawlogReader.cpp). MRPT's deserialisers trust the bytes they read (a
/// corrupt count is allocated as declared, a corrupt type byte can make them
/// dereference null), so the file is first read in a forked child under a
/// memory limit proportional to its inflated size and a CPU limit; a crash or
/// an allocation beyond the limit there is reported as a corrupt entry, and
/// only a file the child read completely is read again here. A file cut
/// inside an entry (a recording that stopped) is read up to its last
/// complete step and `truncation_warning` says where it stopped.
Rawlog readRawlog(const std::string& path, const RawlogReadOptions& options = {});

/// The same for a rawlog already inflated in memory; `name` stands for the
/// file in messages (used by the fuzz target).
Rawlog readRawlogFromMemory(const std::string& name, std::string bytes, const RawlogReadOptions& options = {});

}  // namespace esif
