#pragma once
/// \file Calibration.h
/// `esif calibrate`: the noise model of one or more rawlogs fitted by
/// maximum likelihood (NoiseFit.h) against a reference that gives every
/// measurement its landmark and the trajectory and map (the rawlog's IDs
/// with its ground truth, or a full-SLAM run folder with its
/// associations.txt), checked on windows of many steps
/// (CalibrationChecks.h) and on an EKF's innovations
/// (InnovationLikelihood.h), and written as a calibration file
/// (NoiseCalibration.h) with the checks in its comments.

#include <esif/calibration/CalibrationChecks.h>
#include <esif/calibration/NoiseFit.h>

#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// One rawlog and its reference.
struct CalibrationInput
{
	std::string rawlog;
	/// A run folder of this rawlog (the full-SLAM optimum's): its
	/// associations.txt gives the landmarks, its trajectory and map the
	/// reference. Without it: the rawlog's IDs (or the simulator's
	/// measurement truth) and the ground truth of `ground_truth_prefix`
	/// (else beside the rawlog).
	std::optional<std::string> reference_run;
	std::optional<std::string> ground_truth_prefix;
};

struct CalibrationRequest
{
	std::vector<CalibrationInput> inputs;
	std::string out_path;  ///< the calibration file to write
	NoiseFitSettings settings;
	std::vector<std::size_t> window_lengths = {1, 2, 5, 10, 20, 50, 100, 200};
	/// Consecutive measurements of one landmark (CalibrationChecks.h).
	std::vector<std::size_t> sensor_window_lengths = {1, 4, 16, 64};
};

/// The checks of one rawlog under the rawlog's noise and under the fit.
struct CalibrationInputChecks
{
	std::string rawlog;
	std::string reference;	///< what the checks compare with; empty when there is nothing
	std::vector<OdometryWindowCheck> odometry_before, odometry_after;
	SensorResidualCheck sensor_before, sensor_after;
	std::vector<SensorWindowCheck> sensor_windows_before, sensor_windows_after;
};

struct CalibrationReport
{
	NoiseFitResult fit;
	std::vector<CalibrationInputChecks> checks;
	std::string text;  ///< the human-readable report (also the file's comment)
};

/// Reads, fits, checks and writes request.out_path as a file set of its own
/// (FileSet.h: it replaces only a calibration file esif wrote, never an
/// input). Throws ConfigError/InputError naming the file.
CalibrationReport calibrateNoise(const CalibrationRequest& request);

}  // namespace esif
