/// \file MapOverlayWriter.cpp
/// maps_overlay.png (see MapOverlay.h; cf. the book's side-by-side maps of
/// EKF SLAM and the joined map, Fig. 4.10, 4.16).

#include <esif/render/MapOverlay.h>

#include <esif/core/Errors.h>

#include "MapGeometry.h"
#include "MapPlot.h"
#include "PlotScript.h"

#include <algorithm>
#include <string>
#include <vector>

namespace esif
{
namespace
{
namespace mg = map_geometry;

/// Paths are simplified to this fraction of the view (invisible at 1200 px).
constexpr double kOverlayPathTolerance = 1.0 / 4000.0;

std::vector<Eigen::Vector2d> pathOf(const RunOutputs& run)
{
	std::vector<Eigen::Vector2d> pts;
	pts.reserve(run.trajectory.size());
	for (const auto& p : run.trajectory) pts.emplace_back(p.pose.x, p.pose.y);
	return pts;
}

/// The reference's paths and landmarks, padded by a fifth: one diverged run
/// cannot shrink the others to a dot (what falls outside is clipped).
mg::Bounds frameOf(const RunOutputs& reference)
{
	mg::Bounds b;
	for (const Eigen::Vector2d& p : pathOf(reference)) b.add(p);
	for (const LandmarkEstimate& lm : reference.landmarks) b.add(lm.mean);
	return b.padded(1.0, 0.2);
}

/// Layer i's colour: the reference black, then the twelve series colours.
std::string layerColour(std::size_t i) { return i == 0 ? std::string("#000000") : plot::seriesColour(i - 1); }

/// The path and the landmark clauses of one layer.
std::vector<std::string> layerClauses(plot::Figure& fig, const MapOverlayLayer& layer, std::size_t i, double tolerance)
{
	std::vector<std::string> clauses;
	const std::string lc = "lc rgb '" + layerColour(i) + "'";
	const std::vector<Eigen::Vector2d> path = pathOf(layer.outputs);
	const plot::DataBlock line = map_plot::polyline(path, tolerance);
	plot::DataBlock marks;
	for (const LandmarkEstimate& lm : layer.outputs.landmarks) marks.row({lm.mean.x(), lm.mean.y()});
	const std::string title = "title " + plot::quoted(layer.label);
	if (!line.empty())
		clauses.push_back(fig.add(line) + " using 1:2 with lines lw " + (i == 0 ? "2.5 " : "1.5 ") + lc + " " + title);
	if (!marks.empty())
		clauses.push_back(fig.add(marks) + " using 1:2 with points " + (i == 0 ? "pt 6 ps 1.3 lw 1.5 " : "pt 1 ps 1.1 lw 1.5 ") +
						  lc + " " + (line.empty() ? title : "notitle"));
	return clauses;
}
}  // namespace

void writeMapOverlayImage(
	const std::vector<MapOverlayLayer>& layers, const std::string& title, const std::string& path, int width_px)
{
	plot::validateWidth(width_px, "maps_overlay width");
	if (layers.empty()) throw ConfigError("maps_overlay: no run to draw");
	const mg::Bounds view = frameOf(layers.front().outputs);
	const double tolerance = kOverlayPathTolerance * std::max(view.width(), view.height());
	plot::Figure fig(width_px, width_px * 3 / 4);
	fig.command(plot::chartDefaults());
	fig.command(map_plot::equalScaleAxes(view));
	fig.command("set key outside right top");
	fig.command("set title " + plot::quoted(plot::withBookFigure(title, "Fig. 4.10, 4.16")));
	std::vector<std::string> clauses;
	for (std::size_t i = 0; i < layers.size(); ++i)
		for (std::string& c : layerClauses(fig, layers[i], i, tolerance)) clauses.push_back(std::move(c));
	fig.command(plot::plotCommand(clauses));
	plot::writeFigure(fig, path);
}

}  // namespace esif
