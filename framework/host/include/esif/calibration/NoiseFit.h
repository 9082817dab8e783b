#pragma once
/// \file NoiseFit.h
/// Maximum-likelihood noise model of one or more rawlogs against a
/// reference trajectory and map (ground truth, or a full-SLAM optimum with
/// its association):
/// - systematic odometry errors (distance and turn scale, heading drift
///   per metre), by least squares of the odometry's heading change over
///   windows against the reference's, kept only when a correction fitted
///   on every other window lowers the error of the others;
/// - the odometry noise scales (x-y and heading), by the normalised error of
///   windows of every length up to the horizon H: a Gaussian's variance
///   scale has the ML estimate mean(e^2 / sigma^2), and the largest over
///   the window lengths is kept, so that the odometry is consistent over
///   every stretch a filter bridges with it, not only over one step (an
///   error that behaves like a bias grows faster than sqrt(W));
/// - the range-bearing noise and bias, by ML of a Gaussian mixed with a
///   uniform outlier density (misreads, false detections), by EM.
/// H is the horizon_quantile of the gaps, in steps, between consecutive
/// sightings of one landmark under the reference association: the
/// stretches of odometry a filter's association gate must be consistent
/// over.

#include <esif/calibration/CalibrationChecks.h>
#include <esif/calibration/InnovationLikelihood.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// A rawlog prepared for calibration with its reference.
struct ReferencedLog
{
	CalibrationLog log;	 ///< every measurement carries its reference landmark ID
	std::vector<Pose2> path;  ///< reference pose of each step (initial-pose frame)
	std::map<LandmarkId, Eigen::Vector2d> landmarks;
	/// Whether the reference was fitted to these data (a full-SLAM optimum):
	/// its residuals are then shrunk, and the sensor variance is divided by
	/// the fraction of each landmark's measurements left free by its fit.
	bool fitted_reference = false;
};

struct NoiseFitSettings
{
	bool odometry_bias = true;	///< systematic odometry errors
	bool odometry = true;  ///< odometry_std_scale_xy and _phi
	bool sensor_noise = true;  ///< range_std_m and bearing_std_deg
	bool sensor_bias = true;  ///< range_bias_m and bearing_bias_deg
	double horizon_quantile = 0.9;	///< of the re-observation gaps
	std::optional<std::size_t> horizon_steps;  ///< overrides the quantile
	/// The sensor noise is inflated until sums of up to this many consecutive
	/// sightings of one landmark are consistent (sensorWindowChecks); 1 =
	/// independent measurements. Above 1 the map's covariance stays honest
	/// when each landmark has an error of its own, at the price of looser
	/// association gates.
	std::size_t sensor_horizon = 1;
	LikelihoodOptions likelihood;  ///< outlier prior (sensor fit and innovation check)
};

struct SensorFit
{
	std::size_t measurements = 0, outliers = 0;
};

struct NoiseFitResult
{
	NoiseCalibration start, fitted;
	std::size_t horizon_steps = 0;
	/// Whether the systematic odometry correction passed its held-out test
	/// (NoiseFit.cpp) and was kept.
	bool odometry_bias_held_out = false;
	SensorFit sensor;
	/// The innovations of an EKF with the reference association under
	/// both models (InnovationLikelihood.h): what a gate would see.
	InnovationStats before, after;
};

/// Fits from `start` (the rawlog's noise, range_std_m and bearing_std_deg
/// set). Throws InputError when a log has no reference path or nothing to
/// fit.
NoiseFitResult fitNoise(const std::vector<ReferencedLog>& logs, const NoiseCalibration& start,
						const NoiseFitSettings& settings);

/// The range-bearing noise the logs carry: the median over their
/// measurements of the range and bearing standard deviations (as
/// range_std_m and bearing_std_deg, everything else identity).
NoiseCalibration rawlogNoise(const std::vector<ReferencedLog>& logs);

/// The q-quantile of the steps between consecutive sightings of one
/// landmark (at least 1).
std::size_t reobservationHorizon(const std::vector<ReferencedLog>& logs, double q);

}  // namespace esif
