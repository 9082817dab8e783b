/// \file MonteCarloFigures.cpp
/// anees_pose.png, rmse.png, landmark_anees.png; see MonteCarloFigures.h.

#include "montecarlo/MonteCarloFigures.h"
#include <esif/render/FigureWriter.h>

#include <cmath>
#include <filesystem>

namespace esif
{
namespace
{
constexpr double kRadToDeg = 180.0 / M_PI;

/// The config with the most runs: its bounds are the ones shaded (with
/// equal N every config has the same bounds).
const ConfigStatistics& mostRuns(const std::vector<ConfigStatistics>& configs)
{
	const ConfigStatistics* best = &configs.front();
	for (const auto& c : configs)
		if (c.runs > best->runs) best = &c;
	return *best;
}

std::string boundsLabel(const ConfigStatistics& c, int dof)
{
	return "95% bounds, N = " + std::to_string(c.runs) + " (" + std::to_string(dof) + "N dof)";
}

LineChart poseAneesChart(const std::vector<ConfigStatistics>& configs, const std::string& title)
{
	LinePanel panel{"pose ANEES (3 dof)", {}, {}, true};
	const ConfigStatistics& shaded = mostRuns(configs);
	ShadedBand bounds{boundsLabel(shaded, 3), {}, -1};
	for (const auto& s : shaded.steps)
		if (s.anees) bounds.points.push_back({double(s.step), s.bounds.lo, s.bounds.hi});
	panel.bands.push_back(bounds);
	for (const auto& c : configs)
	{
		LineSeries line{c.name, {}};
		for (const auto& s : c.steps)
			if (s.anees) line.points.emplace_back(double(s.step), *s.anees);
		panel.series.push_back(line);
	}
	return {"pose ANEES over " + std::to_string(shaded.runs) + " runs: " + title, "step", {panel}, "Fig. 3.15"};
}

LineChart rmseChart(const std::vector<ConfigStatistics>& configs, const std::string& title)
{
	// The spread of several configs would hide one another: shaded for one
	// config only (per_step.csv has it for every config).
	const bool shade_spread = configs.size() == 1;
	LinePanel position{
		shade_spread ? "position RMSE over runs [m] (shaded: 10-90 % of the runs' errors)"
					 : "position RMSE over runs [m] (10-90 % spread of each config in per_step.csv)",
		{}, {}, false};
	LinePanel heading{"heading RMSE over runs [deg]", {}, {}, false};
	for (std::size_t i = 0; i < configs.size(); ++i)
	{
		const auto& c = configs[i];
		LineSeries pos{c.name, {}}, head{c.name, {}};
		ShadedBand spread{"", {}, static_cast<int>(i)};
		for (const auto& s : c.steps)
		{
			pos.points.emplace_back(double(s.step), s.position_rmse_m);
			head.points.emplace_back(double(s.step), kRadToDeg * s.heading_rmse_rad);
			spread.points.push_back({double(s.step), s.position_error_p10_m, s.position_error_p90_m});
		}
		position.series.push_back(pos);
		heading.series.push_back(head);
		if (shade_spread) position.bands.push_back(spread);
	}
	return {"error over runs: " + title, "step", {position, heading}, "Fig. 3.15"};
}

LineChart landmarkAneesChart(const std::vector<ConfigStatistics>& configs, const std::string& title)
{
	LinePanel panel{"final landmark ANEES (2 dof)", {}, {}, true};
	const ConfigStatistics& shaded = mostRuns(configs);
	ShadedBand bounds{boundsLabel(shaded, 2), {}, -1};
	for (const auto& c : configs)
	{
		LineSeries dots{c.name, {}, true};
		for (const auto& l : c.landmarks)
			if (l.runs > 0) dots.points.emplace_back(double(l.true_id), l.anees);
		panel.series.push_back(dots);
	}
	// A constant band across the landmark IDs: the bounds of a landmark every run mapped.
	double id_max = 0;
	for (const auto& c : configs)
		for (const auto& l : c.landmarks) id_max = std::max(id_max, double(l.true_id));
	bounds.points.push_back({0.0, shaded.landmark_bounds.lo, shaded.landmark_bounds.hi});
	bounds.points.push_back({id_max, shaded.landmark_bounds.lo, shaded.landmark_bounds.hi});
	panel.bands.push_back(bounds);
	return {"final landmark ANEES per landmark over " + std::to_string(shaded.runs) + " runs: " + title,
			"landmark ID (ground truth)", {panel}, "Fig. 3.9"};
}
}  // namespace

void writeMonteCarloFigures(
	const std::vector<ConfigStatistics>& configs, const std::string& title, const std::string& dir, int width_px)
{
	if (configs.empty()) return;
	const std::filesystem::path d(dir);
	writeLineChartImage(poseAneesChart(configs, title), (d / "anees_pose.png").string(), width_px);
	writeLineChartImage(rmseChart(configs, title), (d / "rmse.png").string(), width_px);
	writeLineChartImage(landmarkAneesChart(configs, title), (d / "landmark_anees.png").string(), width_px);
}

}  // namespace esif
