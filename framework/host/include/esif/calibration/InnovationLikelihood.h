#pragma once
/// \file InnovationLikelihood.h
/// The likelihood of a rawlog's measurements under a noise model, by the
/// prediction-error decomposition (Schweppe 1965; Mehra 1970): an EKF SLAM
/// with the reference's data association is run over the log, and every
/// re-observation of a mapped landmark contributes the density of its
/// innovation, N(nu; 0, S), S = H P H^T + R. The product over the log is
/// the likelihood of the data given the noise model, with the trajectory
/// and the map integrated out to first order, so no residual is shrunk by
/// having been fitted (a full-SLAM optimum's residuals are). It is the
/// quantity an association gate tests: a noise model that maximises it
/// makes the filter's innovations as large as it predicts them, over
/// whatever stretch of odometry separates two sightings, which is where an
/// odometry error that behaves like a bias shows.
///
/// Robust: a measurement is an inlier with probability 1 - outlier_fraction,
/// else uniform over the sensor's range and field of view (a misread or a
/// false detection). A measurement more likely an outlier than not is
/// neither scored as a Gaussian nor fused.

#include <esif/calibration/NoiseCalibration.h>
#include <esif/core/StepInput.h>

#include <string>
#include <vector>

namespace esif
{
/// One rawlog prepared for calibration: every measurement carries the ID of
/// its landmark from the reference association (a measurement without one
/// is left out).
struct CalibrationLog
{
	std::string name;
	std::vector<StepInput> steps;
};

struct LikelihoodOptions
{
	/// Prior probability that a measurement is an outlier, in [0, 1).
	double outlier_fraction = 0.01;
};

struct InnovationStats
{
	/// Negative log-likelihood of the re-observations (nats); +inf when the
	/// filter failed under the model (a covariance not positive definite).
	double nll = 0;
	std::size_t reobservations = 0;	 ///< measurements of mapped landmarks
	std::size_t outliers = 0;  ///< of those, judged more likely outliers
	std::size_t initialisations = 0;  ///< measurements that started a landmark
	/// Mean individual normalised innovation squared of the inliers (2 for a
	/// consistent filter).
	double nis_mean = 0;
	/// Share of re-observations whose individual NIS exceeds chi2_2(0.9999),
	/// what an ID gate at 0.9999 would reject (1e-4 for a consistent filter).
	double above_gate_9999 = 0;
};

/// The likelihood of every log (summed) under `calibration`.
InnovationStats innovationLikelihood(
	const std::vector<CalibrationLog>& logs, const NoiseCalibration& calibration, const LikelihoodOptions& options);

}  // namespace esif
