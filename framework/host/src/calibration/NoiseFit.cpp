#include "NoiseFitParts.h"

#include <esif/calibration/NoiseFit.h>
#include <esif/core/Errors.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace esif
{
namespace
{
double median(std::vector<double> v)
{
	if (v.empty()) return 0;
	std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
	return v[v.size() / 2];
}

std::vector<CalibrationLog> logsOf(const std::vector<ReferencedLog>& logs)
{
	std::vector<CalibrationLog> out;
	for (const auto& l : logs) out.push_back(l.log);
	return out;
}
}  // namespace

NoiseCalibration rawlogNoise(const std::vector<ReferencedLog>& logs)
{
	std::vector<double> range, bearing;
	for (const auto& ref : logs)
		for (const auto& step : ref.log.steps)
			if (step.scan)
				for (const auto& m : step.scan->measurements)
					range.push_back(std::sqrt(m.cov(0, 0))), bearing.push_back(std::sqrt(m.cov(1, 1)));
	NoiseCalibration noise;
	noise.range_std_m = median(range);
	noise.bearing_std_deg = median(bearing) * 180.0 / M_PI;
	return noise;
}

std::size_t reobservationHorizon(const std::vector<ReferencedLog>& logs, double q)
{
	std::vector<double> gaps;
	for (const auto& ref : logs)
	{
		std::unordered_map<LandmarkId, std::size_t> last;
		for (std::size_t k = 0; k < ref.log.steps.size(); ++k)
			if (const auto& scan = ref.log.steps[k].scan)
				for (const auto& m : scan->measurements)
				{
					if (!m.id) continue;
					if (const auto it = last.find(*m.id); it != last.end() && it->second < k)
						gaps.push_back(static_cast<double>(k - it->second));
					last[*m.id] = k;
				}
	}
	if (gaps.empty()) return 1;
	std::sort(gaps.begin(), gaps.end());
	const auto index = static_cast<std::size_t>(std::ceil(q * static_cast<double>(gaps.size()))) ;
	return static_cast<std::size_t>(gaps[std::min(gaps.size() - 1, index == 0 ? 0 : index - 1)]);
}

NoiseFitResult fitNoise(const std::vector<ReferencedLog>& logs, const NoiseCalibration& start,
						const NoiseFitSettings& settings)
{
	for (const auto& l : logs)
		if (l.path.empty())
			throw InputError(l.log.name + ": no reference trajectory to calibrate against (give its ground truth or "
										  "--reference-run)");
	NoiseFitResult result;
	result.start = result.fitted = start;
	result.horizon_steps = settings.horizon_steps.value_or(reobservationHorizon(logs, settings.horizon_quantile));
	// The sensor first: its bias and noise do not depend on the odometry's.
	if (settings.sensor_noise || settings.sensor_bias)
		result.sensor = noise_fit::fitSensor(logs, settings, result.fitted);
	if (settings.odometry_bias)
		result.odometry_bias_held_out =
			noise_fit::fitOdometryBias(logs, std::clamp<std::size_t>(result.horizon_steps, 10, 100), result.fitted);
	if (settings.odometry) noise_fit::fitOdometryNoise(logs, result.horizon_steps, result.fitted);
	const auto calibration_logs = logsOf(logs);
	result.before = innovationLikelihood(calibration_logs, start, settings.likelihood);
	result.after = innovationLikelihood(calibration_logs, result.fitted, settings.likelihood);
	return result;
}

}  // namespace esif
