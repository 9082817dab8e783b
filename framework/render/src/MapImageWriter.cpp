/// \file MapImageWriter.cpp
/// map.png (and map.svg): a top-down picture of the run, the first thing
/// users look at. Over a metric grid with equal scales it shows the
/// estimated path and landmarks (with uncertainty ellipses and IDs), the
/// final robot pose and, when known, the ground truth, with a legend and the
/// plugin name as title (cf. the book's maps, Fig. 3.14, 3.18, 4.10, 4.16).

#include <esif/render/MapRender.h>

#include "MapGeometry.h"
#include "MapPalette.h"
#include "MapPlot.h"
#include "PlotScript.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace esif
{
namespace
{
using namespace esif::map_palette;
namespace mg = map_geometry;

const mrpt::img::TColor kEllipseColor(235, 130, 130);
const mrpt::img::TColor kLandmarkIdColor(150, 60, 60);
const mrpt::img::TColor kRobotColor(10, 30, 120);
const mrpt::img::TColor kMapRobotEllipseColor(120, 140, 230);

/// Landmark IDs are written next to the marks up to this many landmarks;
/// beyond that they only clutter the picture.
constexpr std::size_t kMaxLandmarkIds = 150;
/// Segments of an ellipse: smooth at the few pixels an ellipse spans, and
/// half the vertices of 48 for gnuplot to draw on every landmark.
constexpr int kEllipseSegments = 24;
/// Paths are simplified to this fraction of the view (a third of a pixel at
/// 1000 px): invisible, and 18000-step paths stay light in the SVG.
constexpr double kMapPathTolerance = 1.0 / 3000.0;

/// One layer of the picture: its data and its plot clause.
struct Layer
{
	plot::DataBlock data;
	std::string style;	///< "using ... with ... lc ... title ..."
};

std::string colour(const mrpt::img::TColor& c) { return "lc rgb '" + hex(c) + "'"; }

/// Closed ellipses, one after another, separated by gaps.
void addEllipse(plot::DataBlock& block, const Eigen::Vector2d& mean, const Eigen::Matrix2d& cov, double sigmas)
{
	block.breakLine();
	for (const Eigen::Vector2d& p : mg::ellipsePolygon(mean, cov, sigmas, kEllipseSegments)) block.row({p.x(), p.y()});
}

bool robotIsFinite(const RunRecord& run)
{
	const auto& m = run.final_estimate.robot.mean;
	return std::isfinite(m.x()) && std::isfinite(m.y()) && std::isfinite(m(2));
}

/// The layers bottom-up: truth, ellipses, path, start, marks, IDs, robot.
std::vector<Layer> mapLayers(const RunRecord& run, double sigmas, double view_span)
{
	std::vector<Layer> layers;
	const auto add = [&](plot::DataBlock data, const std::string& style) {
		if (!data.empty()) layers.push_back({std::move(data), style});
	};
	const double tolerance = kMapPathTolerance * view_span;
	if (run.truth)
	{
		add(map_plot::polyline(mg::truthPathXY(run), tolerance), "using 1:2 with lines lw 3 " + colour(kTruthPathColor) + " title 'true path'");
		plot::DataBlock marks;
		for (const auto& [id, p] : run.truth->landmarks) marks.row({p.x(), p.y()});
		add(std::move(marks), "using 1:2 with points pt 1 ps 1.6 lw 1.5 " + colour(kTruthLandmarkColor) + " title 'true landmark'");
	}
	const auto& landmarks = run.final_estimate.landmarks;
	plot::DataBlock ellipses, marks, ids;
	for (const LandmarkEstimate& lm : landmarks)
	{
		if (!mg::isFinite(lm.mean)) continue;
		addEllipse(ellipses, lm.mean, lm.cov, sigmas);
		marks.row({lm.mean.x(), lm.mean.y()});
		if (landmarks.size() <= kMaxLandmarkIds) ids.row({lm.mean.x(), lm.mean.y(), double(lm.id)});
	}
	char ellipse_title[48];
	std::snprintf(ellipse_title, sizeof ellipse_title, "%g-sigma ellipse", sigmas);
	add(std::move(ellipses), "using 1:2 with lines lw 1 " + colour(kEllipseColor) + " title " + plot::quoted(ellipse_title));
	const std::vector<Eigen::Vector2d> path = mg::trajectoryXY(run);
	add(map_plot::polyline(path, tolerance), "using 1:2 with lines lw 2 " + colour(kPathColor) + " title 'estimated path'");
	if (!path.empty() && mg::isFinite(path.front()))
	{
		plot::DataBlock start;
		start.row({path.front().x(), path.front().y()});
		add(std::move(start), "using 1:2 with points pt 6 ps 2 lw 2 lc rgb 'black' title 'start'");
	}
	add(std::move(marks), "using 1:2 with points pt 2 ps 1.2 lw 1.5 " + colour(kLandmarkColor) + " title 'estimated landmark'");
	add(std::move(ids), "using 1:2:(sprintf('%d', $3)) with labels offset 0.9,0.7 font ',8' tc rgb '" +
							hex(kLandmarkIdColor) + "' notitle");
	if (robotIsFinite(run))
	{
		const PoseEstimate& robot = run.final_estimate.robot;
		const Eigen::Vector2d xy(robot.mean.x(), robot.mean.y());
		plot::DataBlock robot_ellipse, arrow;
		addEllipse(robot_ellipse, xy, robot.cov.topLeftCorner<2, 2>(), sigmas);
		add(std::move(robot_ellipse), "using 1:2 with lines lw 1.5 " + colour(kMapRobotEllipseColor) + " notitle");
		const double len = 0.04 * view_span;
		arrow.row({xy.x(), xy.y(), len * std::cos(robot.mean(2)), len * std::sin(robot.mean(2))});
		add(std::move(arrow), "using 1:2:3:4 with vectors filled head size screen 0.015,25 lw 3 " + colour(kRobotColor) +
								  " title 'final pose'");
	}
	return layers;
}

std::string subtitle(const RunRecord& run)
{
	std::string s = std::filesystem::path(run.rawlog).filename().string();
	return s + (s.empty() ? "" : "  -  ") + std::to_string(run.final_estimate.landmarks.size()) + " landmarks, " +
		   std::to_string(run.trajectory.size()) + " steps";
}

plot::Figure mapFigure(const RunRecord& run, const MapWriterOptions& options)
{
	const mg::Bounds view = mg::contentBounds(run, options.ellipse_sigmas).padded(2.0, 0.04);
	const double span = std::max(view.width(), view.height());
	plot::Figure fig(options.image_size_px, options.image_size_px);
	fig.command(plot::chartDefaults());
	fig.command(map_plot::equalScaleAxes(view));
	// The legend in its own band under the x label (gnuplot's "below" key
	// can run into the label once the equal scales shrink the plot).
	fig.command("set bmargin 8\nset key at screen 0.5,0.01 center bottom horizontal maxrows 2");
	fig.command("set title " + plot::twoLines(plot::withBookFigure(run.plugin.empty() ? "esif" : run.plugin, "Fig. 3.14, 4.10"),
								   subtitle(run)));
	std::vector<std::string> clauses;
	for (const Layer& layer : mapLayers(run, options.ellipse_sigmas, span))
		clauses.push_back(fig.add(layer.data) + " " + layer.style);
	fig.command(plot::plotCommand(clauses));
	return fig;
}
}  // namespace

void validateMapWriterOptions(const MapWriterOptions& options) { mg::validateOptions(options); }

void writeMapImage(const RunRecord& run, const std::string& path, const MapWriterOptions& options)
{
	mg::validateOptions(options);
	plot::writeFigure(mapFigure(run, options), path);
}

}  // namespace esif
