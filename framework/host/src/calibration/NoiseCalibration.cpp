#include <esif/calibration/NoiseCalibration.h>
#include <esif/config/ConfigFile.h>
#include <esif/models/Se2.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace esif
{
namespace
{
constexpr double kRadPerDeg = M_PI / 180.0;
}

void NoiseCalibration::declare(ParamBinder& b)
{
	b.real("odometry_distance_scale", odometry_distance_scale,
		   "factor on every odometry increment's translation (a systematic distance error)", Bounds::closed(0.5, 2));
	b.real("odometry_turn_scale", odometry_turn_scale,
		   "factor on every odometry increment's turn (a systematic turn error)", Bounds::closed(0.5, 2));
	b.real("odometry_heading_drift_deg_per_m", odometry_heading_drift_deg_per_m,
		   "heading added per metre driven forward [deg/m] (a systematic drift, e.g. unequal wheels)",
		   Bounds::closed(-10, 10));
	b.real("odometry_std_scale_xy", odometry_std_scale_xy,
		   "factor on the x and y standard deviations of every odometry step's covariance",
		   Bounds::closed(1e-3, 1e3));
	b.real("odometry_std_scale_phi", odometry_std_scale_phi,
		   "factor on the heading standard deviation of every odometry step's covariance", Bounds::closed(1e-3, 1e3));
	b.real("range_std_m", range_std_m, "range noise 1-sigma [m]; 0 = each observation's own",
		   Bounds::closed(0, 1e3));
	b.real("bearing_std_deg", bearing_std_deg, "bearing noise 1-sigma [deg]; 0 = each observation's own",
		   Bounds::closed(0, 90));
	b.real("sighting_range_std_m", sighting_range_std_m,
		   "range noise of one sighting alone, for association tests [m]; 0 = range_std_m", Bounds::closed(0, 1e3));
	b.real("sighting_bearing_std_deg", sighting_bearing_std_deg,
		   "bearing noise of one sighting alone, for association tests [deg]; 0 = bearing_std_deg",
		   Bounds::closed(0, 90));
	b.real("range_bias_m", range_bias_m, "range bias (measured - true) taken out of every measurement [m]",
		   Bounds::closed(-100, 100));
	b.real("bearing_bias_deg", bearing_bias_deg,
		   "bearing bias (measured - true) taken out of every measurement [deg]", Bounds::closed(-45, 45));
}

bool NoiseCalibration::isIdentity() const
{
	return odometry_distance_scale == 1 && odometry_turn_scale == 1 && odometry_heading_drift_deg_per_m == 0 &&
		odometry_std_scale_xy == 1 && odometry_std_scale_phi == 1 && range_std_m == 0 && bearing_std_deg == 0 &&
		sighting_range_std_m == 0 && sighting_bearing_std_deg == 0 && range_bias_m == 0 && bearing_bias_deg == 0;
}

NoiseCalibration loadNoiseCalibration(const std::string& path)
{
	const ConfigFile file = ConfigFile::load(path);
	for (const auto& name : file.sectionNames())
		if (name != kCalibrationSection)
			throw ConfigError(path + ": [" + name + "]: unknown section (a calibration file holds [" +
							  kCalibrationSection + "] only)");
	if (!file.hasSection(kCalibrationSection))
		throw ConfigError(path + ": no [" + std::string(kCalibrationSection) + "] section (write it with esif calibrate)");
	NoiseCalibration calibration;
	const auto section = file.section(kCalibrationSection);
	loadParams(calibration, section);
	section.rejectUnknownKeys();
	return calibration;
}

std::string noiseCalibrationText(const NoiseCalibration& calibration, const std::string& comment)
{
	std::ostringstream out;
	std::istringstream lines(comment);
	for (std::string line; std::getline(lines, line);) out << (line.empty() ? "#" : "# " + line) << "\n";
	out << "\n[" << kCalibrationSection << "]\n";
	for (const auto& p : describeParams(calibration)) out << p.key << " = " << p.value << "\n";
	return out.str();
}

StepInput calibratedStep(const StepInput& step, const NoiseCalibration& c)
{
	StepInput out = step;
	if (out.odometry)
	{
		auto& delta = out.odometry->delta;
		const double forward = std::hypot(delta.x(), delta.y()) * (delta.x() < 0 ? -1 : 1);
		// (2) = heading change
		delta(2) = wrapAngle(c.odometry_turn_scale * delta(2) + c.odometry_heading_drift_deg_per_m * kRadPerDeg * forward);
		delta.x() *= c.odometry_distance_scale;
		delta.y() *= c.odometry_distance_scale;
		const Eigen::Vector3d d(c.odometry_std_scale_xy, c.odometry_std_scale_xy, c.odometry_std_scale_phi);
		out.odometry->cov = d.asDiagonal() * out.odometry->cov * d.asDiagonal();
	}
	if (!out.scan) return out;
	for (auto& m : out.scan->measurements)
	{
		// A range within the bias of zero stays at zero, where a range sensor
		// clips its own readings.
		m.range_m = std::max(0.0, m.range_m - c.range_bias_m);
		m.bearing_rad = wrapAngle(m.bearing_rad - c.bearing_bias_deg * kRadPerDeg);
		if (c.range_std_m > 0 || c.bearing_std_deg > 0) m.cov(0, 1) = m.cov(1, 0) = 0;
		if (c.range_std_m > 0) m.cov(0, 0) = c.range_std_m * c.range_std_m;
		if (c.bearing_std_deg > 0) m.cov(1, 1) = std::pow(c.bearing_std_deg * kRadPerDeg, 2);
	}
	if ((c.sighting_range_std_m > 0 || c.sighting_bearing_std_deg > 0) && !out.scan->measurements.empty())
	{
		// One per scan: the sensor's noise of one sighting, each component
		// not given kept as the fused one.
		Eigen::Matrix2d sighting = out.scan->measurements.front().cov;
		sighting(0, 1) = sighting(1, 0) = 0;
		if (c.sighting_range_std_m > 0) sighting(0, 0) = c.sighting_range_std_m * c.sighting_range_std_m;
		if (c.sighting_bearing_std_deg > 0) sighting(1, 1) = std::pow(c.sighting_bearing_std_deg * kRadPerDeg, 2);
		out.scan->sighting_cov = sighting;
	}
	return out;
}

void applyNoiseCalibration(std::vector<StepInput>& steps, const NoiseCalibration& calibration)
{
	if (calibration.isIdentity()) return;
	for (auto& step : steps) step = calibratedStep(step, calibration);
}

}  // namespace esif
