#include "NoiseFitParts.h"

#include <esif/core/Errors.h>

#include <cmath>
#include <map>

namespace esif::noise_fit
{
namespace
{
struct Residual
{
	double range = 0, bearing = 0;
	double log_outlier_density = 0;	 ///< uniform over the sensor's range x field of view
	LandmarkId landmark = 0;
};

std::vector<Residual> residualsOf(const std::vector<ReferencedLog>& logs)
{
	std::vector<Residual> out;
	for (const auto& ref : logs)
		forEachSensorResidual(ref.log.steps, ref.path, ref.landmarks,
							  [&](const Scan& scan, const RangeBearing& m, double range, double bearing) {
								  const double area = (scan.max_range_m > 0 ? scan.max_range_m : 100.0) *
									  (scan.fov_rad > 0 ? scan.fov_rad : 2 * M_PI);
								  out.push_back({range, bearing, -std::log(area), *m.id});
							  });
	return out;
}

/// Per landmark, the share of its measurements' dimensions left free by a
/// fit that placed it from them: 1 - 1/n for n measurements (its two
/// coordinates are fitted from 2n numbers). 1 against ground truth.
std::map<LandmarkId, double> freeShares(const std::vector<Residual>& residuals, bool fitted)
{
	std::map<LandmarkId, double> n;
	for (const auto& r : residuals) n[r.landmark] += 1;
	for (auto& [id, count] : n) count = fitted ? (count > 1 ? 1 - 1 / count : 0) : 1;
	return n;
}
/// The noise scaled by the square root of the largest normalised window
/// error over 1, 2, 4, ... up to `horizon` consecutive sightings.
void inflateForSightings(const std::vector<ReferencedLog>& logs, std::size_t horizon, NoiseCalibration& c)
{
	std::vector<std::size_t> lengths;
	for (std::size_t w = 1; w < horizon; w *= 2) lengths.push_back(w);
	lengths.push_back(horizon);
	double worst_range = 1, worst_bearing = 1;
	for (const auto& ref : logs)
	{
		auto steps = ref.log.steps;
		applyNoiseCalibration(steps, c);
		for (const auto& w : sensorWindowChecks(steps, ref.path, ref.landmarks, lengths))
			if (w.windows)
				worst_range = std::max(worst_range, w.range_normalised),
				worst_bearing = std::max(worst_bearing, w.bearing_normalised);
	}
	c.range_std_m *= std::sqrt(worst_range);
	c.bearing_std_deg *= std::sqrt(worst_bearing);
}
}  // namespace

SensorFit fitSensor(const std::vector<ReferencedLog>& logs, const NoiseFitSettings& settings, NoiseCalibration& c)
{
	const auto residuals = residualsOf(logs);
	if (residuals.size() < 10) throw InputError("esif calibrate: fewer than 10 measurements of reference landmarks: no sensor fit");
	const bool fitted = std::any_of(logs.begin(), logs.end(), [](const ReferencedLog& l) { return l.fitted_reference; });
	const auto free = freeShares(residuals, fitted);
	const double eps = settings.likelihood.outlier_fraction;
	double sr = c.range_std_m, sb = c.bearing_std_deg / kDegPerRad;
	double br = 0, bb = 0;
	SensorFit fit;
	fit.measurements = residuals.size();
	for (int iteration = 0; iteration < 50; ++iteration)
	{
		// E step: each residual's probability of being an inlier.
		double w_sum = 0, dof_sum = 0, mr = 0, mb = 0, vr = 0, vb = 0;
		std::vector<double> w(residuals.size());
		for (std::size_t i = 0; i < residuals.size(); ++i)
		{
			const auto& r = residuals[i];
			const double zr = (r.range - br) / sr, zb = (r.bearing - bb) / sb;
			const double log_in = std::log1p(-eps) - 0.5 * (zr * zr + zb * zb) - std::log(2 * M_PI * sr * sb);
			const double log_out = (eps > 0 ? std::log(eps) : -INFINITY) + r.log_outlier_density;
			w[i] = 1 / (1 + std::exp(log_out - log_in));
			w_sum += w[i];
			mr += w[i] * r.range;
			mb += w[i] * r.bearing;
		}
		// M step: weighted means (the biases) and variances, the latter over
		// the dimensions a fitted reference left free.
		if (settings.sensor_bias) br = mr / w_sum, bb = mb / w_sum;
		for (std::size_t i = 0; i < residuals.size(); ++i)
		{
			const auto& r = residuals[i];
			vr += w[i] * (r.range - br) * (r.range - br);
			vb += w[i] * (r.bearing - bb) * (r.bearing - bb);
			dof_sum += w[i] * free.at(r.landmark);
		}
		if (!settings.sensor_noise || dof_sum <= 0) break;
		const double new_sr = std::sqrt(vr / dof_sum), new_sb = std::sqrt(vb / dof_sum);
		const bool settled = std::abs(new_sr / sr - 1) < 1e-6 && std::abs(new_sb / sb - 1) < 1e-6;
		sr = new_sr, sb = new_sb;
		fit.outliers = static_cast<std::size_t>(std::count_if(w.begin(), w.end(), [](double x) { return x < 0.5; }));
		if (settled) break;
	}
	if (settings.sensor_noise) c.range_std_m = sr, c.bearing_std_deg = sb * kDegPerRad;
	if (settings.sensor_bias) c.range_bias_m = br, c.bearing_bias_deg = bb * kDegPerRad;
	if (settings.sensor_noise && settings.sensor_horizon > 1)
	{
		// The fit is the noise of one sighting: association tests keep it
		// (Scan::sighting_cov), fusion takes the inflated noise.
		c.sighting_range_std_m = c.range_std_m, c.sighting_bearing_std_deg = c.bearing_std_deg;
		inflateForSightings(logs, settings.sensor_horizon, c);
	}
	return fit;
}

}  // namespace esif::noise_fit
