#pragma once
/// \file MrclamImporter.h
/// One robot of a UTIAS MRCLAM recording (Leung, Halpern, Barfoot, Liu,
/// IJRR 2011; shared/data/mrclam/README.md) as an MRPT actions/sensory-frames
/// rawlog with its ground truth beside it:
/// - one step per distinct time of a landmark measurement; barcodes are
///   translated to subjects through Barcodes.dat, measurements of robots
///   (subjects 1-5) and of barcodes the table does not know are dropped;
/// - the odometry of a step integrates the velocity commands between the
///   two step times (VelocityOdometry.h), with a velocity-model covariance;
/// - the ground truth (NAME_ground_truth.txt with the landmarks,
///   NAME_ground_truth_robot_path.txt with the true pose of every step,
///   Vicon interpolated at the step's time) is in the frame of the robot's
///   true first pose, the frame every esif estimate is in.

#include <esif/models/VelocityOdometry.h>

#include <string>

namespace esif
{
struct MrclamImportOptions
{
	int robot = 1;	///< 1-5
	bool keep_ids = true;  ///< keep the landmark IDs (the subject numbers 6-20)
	/// Range-bearing noise of the camera. Defaults measured on dataset 6,
	/// all five robots, against the Vicon truth (robust spread, misreads
	/// excluded): see the importer's documentation.
	double std_range_m = 0.18;
	double std_bearing_deg = 0.72;
	double max_range_m = 10.0;	///< sensor range stored in the observations (longest measurement 8.6 m)
	double fov_deg = 70.0;	///< field of view stored in the observations (bearings within +-34 deg)
	/// Noise of the commanded velocities the odometry integrates.
	VelocityNoise odometry_noise;
};

struct MrclamImportSummary
{
	std::size_t steps = 0;
	std::size_t measurements = 0;  ///< of landmarks, kept
	std::size_t robot_measurements = 0;	 ///< of other robots, dropped
	std::size_t unknown_barcodes = 0;  ///< of barcodes Barcodes.dat does not list, dropped
	std::size_t landmarks = 0;	///< distinct landmarks measured
	double duration_s = 0;	///< first to last step
	double longest_gap_s = 0;  ///< longest time between two steps
};

/// Reads robot `options.robot` of the recording in `dataset_dir` and writes
/// `out_rawlog` and its ground truth (groundTruthPrefixFor(out_rawlog)),
/// each atomically. Throws InputError naming the file and line for a
/// malformed line, ConfigError for a bad option.
MrclamImportSummary importMrclam(
	const std::string& dataset_dir, const std::string& out_rawlog, const MrclamImportOptions& options);

}  // namespace esif
