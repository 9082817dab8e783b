#include "CalibrationReportText.h"


#include <cmath>
#include <cstdio>
#include <sstream>

namespace esif
{
namespace
{
std::string fixed(double v, int digits)
{
	char buf[64];
	std::snprintf(buf, sizeof buf, "%.*f", digits, v);
	return buf;
}

void parameterTable(std::ostream& out, const NoiseFitResult& fit)
{
	const auto row = [&](const char* name, double before, double after, int digits) {
		out << "| " << name << " | " << fixed(before, digits) << " | " << fixed(after, digits) << " |\n";
	};
	out << "| parameter | rawlog | fitted |\n|---|---:|---:|\n";
	row("odometry_distance_scale", fit.start.odometry_distance_scale, fit.fitted.odometry_distance_scale, 4);
	row("odometry_turn_scale", fit.start.odometry_turn_scale, fit.fitted.odometry_turn_scale, 4);
	row("odometry_heading_drift_deg_per_m", fit.start.odometry_heading_drift_deg_per_m,
		fit.fitted.odometry_heading_drift_deg_per_m, 4);
	row("odometry_std_scale_xy", fit.start.odometry_std_scale_xy, fit.fitted.odometry_std_scale_xy, 3);
	row("odometry_std_scale_phi", fit.start.odometry_std_scale_phi, fit.fitted.odometry_std_scale_phi, 3);
	row("range_std_m", fit.start.range_std_m, fit.fitted.range_std_m, 4);
	row("bearing_std_deg", fit.start.bearing_std_deg, fit.fitted.bearing_std_deg, 3);
	if (fit.fitted.sighting_range_std_m > 0 || fit.fitted.sighting_bearing_std_deg > 0)
	{
		row("sighting_range_std_m (association)", fit.start.range_std_m, fit.fitted.sighting_range_std_m, 4);
		row("sighting_bearing_std_deg (association)", fit.start.bearing_std_deg, fit.fitted.sighting_bearing_std_deg, 3);
	}
	row("range_bias_m", fit.start.range_bias_m, fit.fitted.range_bias_m, 4);
	row("bearing_bias_deg", fit.start.bearing_bias_deg, fit.fitted.bearing_bias_deg, 3);
}

void innovationTable(std::ostream& out, const NoiseFitResult& fit)
{
	const auto row = [&](const char* name, const InnovationStats& s) {
		out << "| " << name << " | " << fixed(s.nll, 1) << " | " << fixed(s.nis_mean, 2) << " | "
			<< fixed(100 * s.above_gate_9999, 2) << "% | " << s.outliers << " of " << s.reobservations << " |\n";
	};
	out << "| model | -log likelihood | mean NIS (2 if consistent) | NIS > chi2_2(0.9999) (0.01% if consistent) | "
		   "judged outliers |\n"
		<< "|---|---:|---:|---:|---:|\n";
	row("rawlog", fit.before);
	row("fitted", fit.after);
}

void windowTable(std::ostream& out, const CalibrationInputChecks& c)
{
	out << "| W steps | windows | x: rawlog / fitted | y | heading | heading RMS [deg] |\n"
		<< "|---:|---:|---:|---:|---:|---:|\n";
	for (std::size_t i = 0; i < c.odometry_before.size(); ++i)
	{
		const auto &b = c.odometry_before[i], &a = c.odometry_after[i];
		if (b.windows == 0) continue;
		out << "| " << b.steps << " | " << b.windows;
		for (int k = 0; k < 3; ++k)
			out << " | " << fixed(b.normalised_error(k), 2) << " / " << fixed(a.normalised_error(k), 2);
		out << " | " << fixed(b.heading_rms_rad * 180 / M_PI, 2) << " |\n";
	}
}

void sensorTable(std::ostream& out, const CalibrationInputChecks& c)
{
	const auto &b = c.sensor_before, &a = c.sensor_after;
	out << "| sensor | mean | RMS | (error/sigma)^2: rawlog / fitted |\n|---|---:|---:|---:|\n"
		<< "| range [m] | " << fixed(b.range_mean_m, 4) << " | " << fixed(b.range_rms_m, 4) << " | "
		<< fixed(b.range_normalised, 2) << " / " << fixed(a.range_normalised, 2) << " |\n"
		<< "| bearing [deg] | " << fixed(b.bearing_mean_rad * 180 / M_PI, 3) << " | "
		<< fixed(b.bearing_rms_rad * 180 / M_PI, 3) << " | " << fixed(b.bearing_normalised, 2) << " / "
		<< fixed(a.bearing_normalised, 2) << " |\n";
}
void sensorWindowTable(std::ostream& out, const CalibrationInputChecks& c)
{
	out << "| W sightings of one landmark | windows | range: rawlog / fitted | bearing |\n|---:|---:|---:|---:|\n";
	for (std::size_t i = 0; i < c.sensor_windows_before.size(); ++i)
	{
		const auto &b = c.sensor_windows_before[i], &a = c.sensor_windows_after[i];
		if (b.windows == 0) continue;
		out << "| " << b.measurements << " | " << b.windows << " | " << fixed(b.range_normalised, 2) << " / "
			<< fixed(a.range_normalised, 2) << " | " << fixed(b.bearing_normalised, 2) << " / "
			<< fixed(a.bearing_normalised, 2) << " |\n";
	}
}
}  // namespace

std::string calibrationReportText(const CalibrationReport& report, const NoiseFitSettings& settings)
{
	std::ostringstream out;
	out << "Written by esif calibrate: the noise model of " << report.checks.size()
		<< " rawlog(s) fitted by maximum likelihood against the reference's\n"
		   "trajectory and map (esif/calibration/NoiseFit.h). Odometry consistent over windows of up to "
		<< report.fit.horizon_steps << " steps\n(the " << settings.horizon_quantile
		<< " quantile of the steps between two sightings of one landmark";
	if (settings.horizon_steps) out << ", set by --horizon-steps";
	out << ");\nsystematic odometry errors: "
		<< (!settings.odometry_bias ? "not fitted"
			: report.fit.odometry_bias_held_out ? "kept (the correction fitted on every other window lowers the error of the others)"
												: "not kept (a correction fitted on every other window does not lower the error of the others)")
		<< "; sensor: " << report.fit.sensor.outliers << " of " << report.fit.sensor.measurements
		<< " measurements judged outliers (prior " << settings.likelihood.outlier_fraction << ")";
	if (settings.sensor_horizon > 1)
		out << ", noise inflated for sums of up to " << settings.sensor_horizon
			<< " sightings of one landmark (association tests keep the noise of one sighting)";
	out << ".\n";
	for (const auto& c : report.checks) out << "rawlog: " << c.rawlog << (c.reference.empty() ? "" : ", reference: " + c.reference) << "\n";
	out << "\n";
	parameterTable(out, report.fit);
	out << "\nCheck: innovations of the re-observed landmarks in an EKF with the reference association (what an\n"
		   "association gate sees):\n\n";
	innovationTable(out, report.fit);
	for (const auto& c : report.checks)
	{
		if (c.reference.empty())
		{
			out << "\n" << c.rawlog << ": no reference trajectory, no checks.\n";
			continue;
		}
		out << "\n" << c.rawlog << " against " << c.reference
			<< ": odometry over windows of W steps, mean (error/sigma)^2 per component (1 when consistent;\n"
			   "growing with W: an error that behaves like a bias; against a fitted optimum rather than ground\n"
			   "truth the short windows read low, its residuals being shrunk by the fit):\n\n";
		windowTable(out, c);
		out << "\n";
		sensorTable(out, c);
		out << "\nSensor residuals summed over W consecutive sightings of one landmark, (sum/sigma)^2 / W (1 when the\n"
			   "errors are independent; growing with W: each landmark has an error of its own, and a map averaging\n"
			   "many sightings is over-confident however right the one-measurement noise is):\n\n";
		sensorWindowTable(out, c);
	}
	return out.str();
}

}  // namespace esif
