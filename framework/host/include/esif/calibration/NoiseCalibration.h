#pragma once
/// \file NoiseCalibration.h
/// A rawlog's noise model as `esif calibrate` fits it and `esif run` applies
/// it: the odometry covariance of every step scaled, the range-bearing
/// noise replaced and a constant sensor bias taken out. The values live in
/// a calibration file (section `[calibration]`) that a config names with
/// `[esif] calibration = FILE`, so all the configs of one dataset share one
/// calibration and a recalibration touches one file.

#include <esif/config/ParamBinder.h>
#include <esif/core/StepInput.h>

#include <string>
#include <vector>

namespace esif
{
struct NoiseCalibration
{
	/// Systematic odometry errors taken out of every increment: the distance
	/// (dx, dy) multiplied by odometry_distance_scale, the turn by
	/// odometry_turn_scale, and odometry_heading_drift_deg_per_m added per
	/// metre driven forward (a wheel-radius mismatch turns the robot as it
	/// drives): dphi' = turn_scale dphi + drift * sign(dx) |(dx, dy)|.
	double odometry_distance_scale = 1;
	double odometry_turn_scale = 1;
	double odometry_heading_drift_deg_per_m = 0;
	/// Factors on the standard deviations of each step's odometry
	/// covariance: x and y scaled by the first, the heading by the second
	/// (covariance D C D, D = diag(xy, xy, phi)), so that the rawlog's own
	/// shape of the noise (per step, per distance) is kept.
	double odometry_std_scale_xy = 1;
	double odometry_std_scale_phi = 1;
	/// Range-bearing noise (1 sigma); 0 keeps each observation's own.
	double range_std_m = 0;
	double bearing_std_deg = 0;
	/// The noise of a single sighting (1 sigma), when range_std_m and
	/// bearing_std_deg are inflated for errors that repeat over the sightings
	/// of one landmark (esif calibrate --sensor-horizon): what association
	/// tests use (Scan::sighting_cov). 0 = as the fused noise.
	double sighting_range_std_m = 0;
	double sighting_bearing_std_deg = 0;
	/// Constant bias of the sensor, measured minus true: taken out of every
	/// measurement (range - bias, bearing - bias).
	double range_bias_m = 0;
	double bearing_bias_deg = 0;

	void declare(ParamBinder& b);
	/// Whether applying it changes nothing.
	bool isIdentity() const;
};

/// Name of the section of a calibration file.
constexpr const char* kCalibrationSection = "calibration";

/// Reads the `[calibration]` section of `path` strictly (ConfigFile rules:
/// unknown keys, sections other than [calibration] and out-of-range values
/// are ConfigErrors naming the file and key).
NoiseCalibration loadNoiseCalibration(const std::string& path);

/// The calibration file's text: `comment` (each line prefixed with "# ")
/// then the `[calibration]` section with every key.
std::string noiseCalibrationText(const NoiseCalibration& calibration, const std::string& comment);

/// `step` with the calibration applied (systematic odometry errors taken
/// out, odometry covariance scaled, sensor bias taken out of every
/// measurement, a range never below zero, its noise replaced when set, its
/// sighting noise set when given).
StepInput calibratedStep(const StepInput& step, const NoiseCalibration& calibration);

/// calibratedStep() of every step, in place.
void applyNoiseCalibration(std::vector<StepInput>& steps, const NoiseCalibration& calibration);

}  // namespace esif
