#pragma once
/// \file NoiseFitParts.h
/// The three fits NoiseFit.cpp chains (see NoiseFit.h for the method).

#include <esif/calibration/NoiseFit.h>

namespace esif::noise_fit
{
constexpr double kDegPerRad = 180.0 / M_PI;

/// Systematic odometry errors: odometry_turn_scale and
/// odometry_heading_drift_deg_per_m by least squares of the heading change
/// over windows of `window` steps, and odometry_distance_scale (the ratio
/// of the reference's path length to the odometry's). Set only when the
/// heading correction fitted on every other window lowers the error of the
/// windows left out, both ways; returns whether it was.
bool fitOdometryBias(const std::vector<ReferencedLog>& logs, std::size_t window, NoiseCalibration& calibration);

/// Odometry noise scales: the largest normalised window error over the
/// lengths 1, 2, 4, ... up to `horizon`, for x-y and for the heading,
/// iterated because the heading noise spreads into x-y over a window.
void fitOdometryNoise(const std::vector<ReferencedLog>& logs, std::size_t horizon, NoiseCalibration& calibration);

/// Range-bearing noise and bias by EM on the residuals against the
/// reference (Gaussian + uniform outliers).
SensorFit fitSensor(const std::vector<ReferencedLog>& logs, const NoiseFitSettings& settings,
					NoiseCalibration& calibration);

}  // namespace esif::noise_fit
