/// \file MapImageWriter.cpp
/// map.png: a top-down picture of the run, the first thing users look at. It
/// shows, over a metric grid with a scale bar, the estimated path and
/// landmarks (with uncertainty ellipses and IDs), the final robot pose and,
/// when known, the ground truth, with a legend and the plugin name as title.

#include <esif/core/Errors.h>
#include <esif/render/MapRender.h>
#include <esif/safeio/AtomicFile.h>

#include "FigureCanvas.h"
#include "MapGeometry.h"
#include "MapPalette.h"

#include <mrpt/img/CImage.h>
#include <mrpt/img/TColor.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace esif
{
namespace
{
using mrpt::img::TColor;
using namespace esif::map_palette;
namespace mg = map_geometry;

const TColor kBackground(255, 255, 255);
const TColor kGridColor(232, 232, 232);
const TColor kGridLabelColor(150, 150, 150);
const TColor kFrameColor(170, 170, 170);
const TColor kTextColor(40, 40, 40);
const TColor kLandmarkIdColor(150, 60, 60);
const TColor kEllipseColor(235, 130, 130);
const TColor kRobotColor(10, 30, 120);
const TColor kRobotEllipseColor(120, 140, 230);
const TColor kStartColor(0, 0, 0);

/// Landmark IDs are written next to the marks up to this many landmarks;
/// beyond that they only clutter the picture.
constexpr std::size_t kMaxLandmarkIds = 150;

// MRPT's bitmap fonts and text drawing, shared with the other figures.
using figure_canvas::Font;
using figure_canvas::kFontLarge;
using figure_canvas::kFontMedium;
using figure_canvas::kFontSmall;
using figure_canvas::kFontTiny;
using figure_canvas::text;
using figure_canvas::textWidth;

/// Pixel rectangle, corners included.
struct Rect
{
	int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
	bool empty() const { return x1 < x0 || y1 < y0; }
	bool contains(int x, int y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
	bool intersects(const Rect& o) const
	{
		return !empty() && !o.empty() && x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1;
	}
};

/// Line widths, mark sizes and fonts for an image size: tuned at 1000 px and
/// scaled so that small and large images look alike.
struct Style
{
	unsigned thick;	 ///< path and mark line width [px]
	int mark;  ///< half size of landmark marks [px]
	Font title;
	Font body;
	Font label;	 ///< grid labels and landmark IDs

	explicit Style(int n)
		: thick(std::max(1u, static_cast<unsigned>(std::lround(2.0 * n / 1000)))),
		  mark(std::max(3, static_cast<int>(std::lround(5.0 * n / 1000)))),
		  title(n >= 600 ? kFontLarge : kFontMedium),
		  body(n >= 600 ? kFontMedium : kFontSmall),
		  label(n >= 600 ? kFontSmall : kFontTiny)
	{
	}
};

/// World (x right, y up) to image pixels (y down), equal scale on both axes.
class PixelMap
{
   public:
	PixelMap() = default;

	/// Fits `world` into `area` at `shrink` (<= 1) times the largest scale;
	/// `align_x`/`align_y` in [0, 1] place it in the spare room: 0 = left/top,
	/// 0.5 = centred, 1 = right/bottom.
	PixelMap(const mg::Bounds& world, const Rect& area, double shrink = 1, double align_x = 0.5, double align_y = 0.5)
	{
		const double w = area.x1 - area.x0, h = area.y1 - area.y0;
		scale_ = shrink * std::min(w / world.width(), h / world.height());
		if (!std::isfinite(scale_) || scale_ <= 0) scale_ = 1;	// degenerate extents far from the origin
		ox_ = area.x0 + align_x * (w - scale_ * world.width()) - scale_ * world.x_min;
		oy_ = area.y0 + align_y * (h - scale_ * world.height()) + scale_ * world.y_max;
	}

	double scale() const { return scale_; }	 ///< pixels per metre
	double px(double x) const { return ox_ + scale_ * x; }
	double py(double y) const { return oy_ - scale_ * y; }	// image y points down
	double wx(double px) const { return (px - ox_) / scale_; }
	double wy(double py) const { return (oy_ - py) / scale_; }

	/// Rounded pixel coordinates, clamped far outside the image so that huge
	/// values cannot overflow int (OpenCV clips the rest).
	std::array<int, 2> pixel(const Eigen::Vector2d& p) const
	{
		return {toPixel(px(p.x())), toPixel(py(p.y()))};
	}
	static int toPixel(double v) { return static_cast<int>(std::lround(std::clamp(v, -1e6, 1e6))); }

   private:
	double scale_ = 1, ox_ = 0, oy_ = 0;
};

// --- Drawing primitives (pixel coordinates) ---------------------------------

void cross(mrpt::img::CImage& img, int x, int y, int half, const TColor& color, unsigned width)
{
	img.line(x - half, y, x + half, y, color, width);
	img.line(x, y - half, x, y + half, color, width);
}

void diagonalCross(mrpt::img::CImage& img, int x, int y, int half, const TColor& color, unsigned width)
{
	img.line(x - half, y - half, x + half, y + half, color, width);
	img.line(x - half, y + half, x + half, y - half, color, width);
}

void polygon(mrpt::img::CImage& img, const std::vector<Eigen::Vector2d>& px, const TColor& color, unsigned width)
{
	for (std::size_t i = 1; i < px.size(); ++i)
		img.line(
			PixelMap::toPixel(px[i - 1].x()), PixelMap::toPixel(px[i - 1].y()), PixelMap::toPixel(px[i].x()),
			PixelMap::toPixel(px[i].y()), color, width);
}

/// Filled triangle by horizontal spans (CCanvas only draws outlines).
void filledTriangle(mrpt::img::CImage& img, std::array<Eigen::Vector2d, 3> v, const TColor& color)
{
	std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.y() < b.y(); });
	const auto xAt = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, double y) {
		return b.y() == a.y() ? a.x() : a.x() + (b.x() - a.x()) * (y - a.y()) / (b.y() - a.y());
	};
	for (int y = static_cast<int>(std::ceil(v[0].y())); y <= static_cast<int>(std::floor(v[2].y())); ++y)
	{
		const double xa = xAt(v[0], v[2], y);
		const double xb = y < v[1].y() ? xAt(v[0], v[1], y) : xAt(v[1], v[2], y);
		img.line(PixelMap::toPixel(std::min(xa, xb)), y, PixelMap::toPixel(std::max(xa, xb)), y, color, 1);
	}
}

/// The robot as a triangle pointing along `heading` (image frame, y down).
void robotGlyph(mrpt::img::CImage& img, double x, double y, double heading, double size, const TColor& color)
{
	const Eigen::Vector2d c(x, y), f(std::cos(heading), std::sin(heading)), s(-f.y(), f.x());
	filledTriangle(
		img, {c + size * f, c - 0.6 * size * f + 0.6 * size * s, c - 0.6 * size * f - 0.6 * size * s}, color);
}

/// One legend row: a glyph centred at (x, y) and its label.
struct LegendEntry
{
	std::string label;
	std::function<void(mrpt::img::CImage&, int x, int y)> glyph;
};

/// Paints one run. Layers are drawn bottom-up (grid, truth, ellipses, path,
/// marks, robot); then the margins are blanked, which clips whatever reached
/// past the plot area, and the annotations go on top.
class MapPainter
{
   public:
	MapPainter(const RunRecord& run, const MapWriterOptions& options)
		: run_(run),
		  sigmas_(options.ellipse_sigmas),
		  n_(options.image_size_px),
		  style_(n_),
		  // Title band above the plot; scale bar band below it.
		  area_{12, style_.title.h + style_.body.h + 24, n_ - 13, n_ - style_.body.h - 22},
		  traj_(mg::trajectoryXY(run)),
		  truth_path_(mg::truthPathXY(run)),
		  legend_(legendEntries()),
		  img_(n_, n_, mrpt::img::CH_RGB)
	{
		placeMapAndLegend();
		// Grid step: about ten cells across the plot area's larger side.
		step_ = mg::niceStep(std::max(area_.x1 - area_.x0, area_.y1 - area_.y0) / map_.scale(), 10);
	}

	mrpt::img::CImage paint()
	{
		img_.filledRectangle(0, 0, n_ - 1, n_ - 1, kBackground);  // CImage(w, h) is uninitialised
		drawGridLines();
		drawTruth();
		drawEstimate();
		clipToPlotArea();
		drawLegend();
		drawGridLabels();
		drawScaleBar();
		drawTitle();
		return img_;
	}

   private:
	// --- Layout -------------------------------------------------------------

	/// Legend rows, a glyph and a label each, for the items this run has.
	std::vector<LegendEntry> legendEntries() const
	{
		const unsigned thick = style_.thick;
		const int mark = style_.mark, half = kGlyphHalf;
		std::vector<LegendEntry> e;
		if (!traj_.empty())
			e.push_back({"estimated path", [=](mrpt::img::CImage& im, int x, int y) {
							 im.line(x - half, y, x + half, y, kPathColor, thick);
						 }});
		if (!run_.final_estimate.landmarks.empty())
		{
			e.push_back({"estimated landmark", [=](mrpt::img::CImage& im, int x, int y) {
							 diagonalCross(im, x, y, mark - 1, kLandmarkColor, thick);
						 }});
			char ellipse_label[48];
			std::snprintf(ellipse_label, sizeof(ellipse_label), "%g-sigma ellipse", sigmas_);
			e.push_back({ellipse_label, [=](mrpt::img::CImage& im, int x, int y) {
							 // An 11 x 6 px ellipse: a pixel-space covariance at 1 sigma.
							 const Eigen::Matrix2d cov_px2 = Eigen::Vector2d(121, 36).asDiagonal();
							 polygon(im, mg::ellipsePolygon(Eigen::Vector2d(x, y), cov_px2, 1.0, 32), kEllipseColor, 1);
						 }});
		}
		if (robotIsFinite())
			e.push_back({"final pose", [=](mrpt::img::CImage& im, int x, int y) {
							 robotGlyph(im, x - mark / 2, y, 0.0, 2.6 * mark, kRobotColor);
						 }});
		if (!traj_.empty())
			e.push_back({"start", [=](mrpt::img::CImage& im, int x, int y) {
							 im.drawCircle(x, y, mark, kStartColor, thick);
						 }});
		if (run_.truth)
		{
			e.push_back({"true path", [=](mrpt::img::CImage& im, int x, int y) {
							 im.line(x - half, y, x + half, y, kTruthPathColor, thick + 1);
						 }});
			e.push_back({"true landmark", [=](mrpt::img::CImage& im, int x, int y) {
							 cross(im, x, y, mark + 1, kTruthLandmarkColor, thick);
						 }});
		}
		return e;
	}

	int legendRowHeight() const { return std::max(style_.body.h + 6, 2 * style_.mark + 6); }

	/// Points standing for everything drawn, for the legend to avoid: marks,
	/// the robot and the paths sampled every few pixels at full scale.
	std::vector<Eigen::Vector2d> obstaclePoints(double full_scale) const
	{
		std::vector<Eigen::Vector2d> pts;
		const double spacing = 3.0 / full_scale;
		const auto addPath = [&](const std::vector<Eigen::Vector2d>& path) {
			const std::vector<std::size_t> keep = mg::simplifiedIndices(path, 0.3 / full_scale);
			if (keep.size() == 1) pts.push_back(path[keep[0]]);
			for (std::size_t k = 1; k < keep.size(); ++k)
			{
				const Eigen::Vector2d a = path[keep[k - 1]], b = path[keep[k]];
				const int n = static_cast<int>(std::min(1e4, std::ceil((b - a).norm() / spacing)));
				for (int i = 0; i < n; ++i) pts.push_back(a + (b - a) * (static_cast<double>(i) / n));
				pts.push_back(b);
			}
		};
		addPath(traj_);
		addPath(truth_path_);
		for (const auto& lm : run_.final_estimate.landmarks)
			if (mg::isFinite(lm.mean)) pts.push_back(lm.mean);
		if (run_.truth)
			for (const auto& [id, p] : run_.truth->landmarks)
				if (mg::isFinite(p)) pts.push_back(p);
		if (robotIsFinite())
			pts.emplace_back(run_.final_estimate.robot.mean.x, run_.final_estimate.robot.mean.y);
		return pts;
	}

	/// Chooses the map placement and the legend corner so that the legend
	/// hides nothing: at full scale with the map centred if a corner is free,
	/// else with the map pushed away from that corner, else shrinking the map
	/// step by step. A map that fills every corner even at 60% keeps full
	/// scale, with the legend where it hides the fewest points.
	void placeMapAndLegend()
	{
		const mg::Bounds world = mg::contentBounds(run_, sigmas_).padded(2.0, 0.03);
		const PixelMap full(world, area_);
		if (legend_.empty())
		{
			map_ = full;
			return;
		}
		const Font& f = style_.body;
		int label_w = 0;
		for (const auto& e : legend_) label_w = std::max(label_w, textWidth(e.label, f));
		const int w = 2 * kGlyphHalf + 24 + label_w, h = static_cast<int>(legend_.size()) * legendRowHeight() + 12;
		const int pad = 10;
		struct Corner
		{
			Rect box;
			double push_x, push_y;	///< map alignment that moves it away from the box
		};
		const std::array<Corner, 4> corners = {{
			{{area_.x0 + pad, area_.y0 + pad, area_.x0 + pad + w, area_.y0 + pad + h}, 1.0, 1.0},
			{{area_.x1 - pad - w, area_.y0 + pad, area_.x1 - pad, area_.y0 + pad + h}, 0.0, 1.0},
			{{area_.x0 + pad, area_.y1 - pad - h, area_.x0 + pad + w, area_.y1 - pad}, 1.0, 0.0},
			{{area_.x1 - pad - w, area_.y1 - pad - h, area_.x1 - pad, area_.y1 - pad}, 0.0, 0.0},
		}};

		const std::vector<Eigen::Vector2d> obstacles = obstaclePoints(full.scale());
		// Clearance around the box: marks have a size.
		const int clear = style_.mark + static_cast<int>(style_.thick) + 2;
		const auto hidden = [&](const PixelMap& m, const Rect& r) {
			const Rect grown{r.x0 - clear, r.y0 - clear, r.x1 + clear, r.y1 + clear};
			std::size_t count = 0;
			for (const auto& p : obstacles)
			{
				const auto q = m.pixel(p);
				if (grown.contains(q[0], q[1])) ++count;
			}
			return count;
		};

		for (double shrink = 1.0; shrink > 0.59; shrink -= 0.04)
		{
			for (const Corner& c : corners)
			{
				const PixelMap centred(world, area_, shrink);
				if (hidden(centred, c.box) == 0)
				{
					map_ = centred;
					legend_box_ = c.box;
					return;
				}
			}
			for (const Corner& c : corners)
			{
				const PixelMap pushed(world, area_, shrink, c.push_x, c.push_y);
				if (hidden(pushed, c.box) == 0)
				{
					map_ = pushed;
					legend_box_ = c.box;
					return;
				}
			}
		}
		map_ = full;
		std::size_t best = std::numeric_limits<std::size_t>::max();
		for (const Corner& c : corners)
		{
			const std::size_t k = hidden(full, c.box);
			if (k < best)
			{
				best = k;
				legend_box_ = c.box;
			}
		}
	}

	// --- Layers -------------------------------------------------------------

	void drawGridLines()
	{
		// Integer multiples of the step, so that far from the origin (where
		// adding a small step may not change a double) the loop still ends.
		const auto multiples = [&](double lo, double hi) {
			std::vector<double> v;
			const double first = std::ceil(lo / step_);
			for (int i = 0; i <= 1000 && (first + i) * step_ <= hi; ++i) v.push_back((first + i) * step_);
			return v;
		};
		for (const double gx : multiples(map_.wx(area_.x0), map_.wx(area_.x1)))
		{
			const int x = PixelMap::toPixel(map_.px(gx));
			img_.line(x, area_.y0, x, area_.y1, kGridColor, 1);
			x_grid_.emplace_back(x, gx);
		}
		for (const double gy : multiples(map_.wy(area_.y1), map_.wy(area_.y0)))
		{
			const int y = PixelMap::toPixel(map_.py(gy));
			img_.line(area_.x0, y, area_.x1, y, kGridColor, 1);
			y_grid_.emplace_back(y, gy);
		}
	}

	/// Polyline through `pts`, simplified to a third of a pixel (invisible,
	/// and it keeps 18000-step paths quick to draw).
	void path(const std::vector<Eigen::Vector2d>& pts, const TColor& color, unsigned width)
	{
		const std::vector<std::size_t> keep = mg::simplifiedIndices(pts, 0.3 / map_.scale());
		for (std::size_t k = 1; k < keep.size(); ++k)
		{
			const auto a = map_.pixel(pts[keep[k - 1]]);
			const auto b = map_.pixel(pts[keep[k]]);
			img_.line(a[0], a[1], b[0], b[1], color, width);
		}
	}

	/// The `sigmas_` ellipse of a world covariance.
	void ellipse(const Eigen::Vector2d& mean, const Eigen::Matrix2d& cov, const TColor& color)
	{
		std::vector<Eigen::Vector2d> poly = mg::ellipsePolygon(mean, cov, sigmas_, 48);
		for (Eigen::Vector2d& p : poly) p = Eigen::Vector2d(map_.px(p.x()), map_.py(p.y()));
		polygon(img_, poly, color, 1);
	}

	void drawTruth()
	{
		if (!run_.truth) return;
		path(truth_path_, kTruthPathColor, style_.thick + 1);
		for (const auto& [id, p] : run_.truth->landmarks)
		{
			if (!mg::isFinite(p)) continue;
			const auto q = map_.pixel(p);
			cross(img_, q[0], q[1], style_.mark + 1, kTruthLandmarkColor, style_.thick);
		}
	}

	void drawEstimate()
	{
		const auto& landmarks = run_.final_estimate.landmarks;
		// Ellipses first, so they do not hide the path or the marks.
		for (const LandmarkEstimate& lm : landmarks)
			if (mg::isFinite(lm.mean)) ellipse(lm.mean, lm.cov, kEllipseColor);

		path(traj_, kPathColor, style_.thick);
		if (!traj_.empty() && mg::isFinite(traj_.front()))
		{
			const auto s = map_.pixel(traj_.front());
			img_.drawCircle(s[0], s[1], style_.mark, kStartColor, style_.thick);
		}

		for (const LandmarkEstimate& lm : landmarks)
		{
			if (!mg::isFinite(lm.mean)) continue;
			const auto q = map_.pixel(lm.mean);
			diagonalCross(img_, q[0], q[1], style_.mark - 1, kLandmarkColor, style_.thick);
			if (landmarks.size() <= kMaxLandmarkIds)
				text(img_, q[0] + style_.mark + 1, q[1] - style_.mark - style_.label.h + 2, std::to_string(lm.id),
					 style_.label, kLandmarkIdColor);
		}

		const PoseEstimate& robot = run_.final_estimate.robot;
		if (robotIsFinite())
		{
			const Eigen::Vector2d xy(robot.mean.x, robot.mean.y);
			ellipse(xy, robot.cov.topLeftCorner<2, 2>(), kRobotEllipseColor);
			// Heading negated: image y points down.
			robotGlyph(img_, map_.px(xy.x()), map_.py(xy.y()), -robot.mean.phi, 3.2 * style_.mark, kRobotColor);
		}
	}

	bool robotIsFinite() const
	{
		const auto& m = run_.final_estimate.robot.mean;
		return std::isfinite(m.x) && std::isfinite(m.y) && std::isfinite(m.phi);
	}

	// --- Annotations --------------------------------------------------------

	void clipToPlotArea()
	{
		img_.filledRectangle(0, 0, n_ - 1, area_.y0 - 1, kBackground);
		img_.filledRectangle(0, area_.y1 + 1, n_ - 1, n_ - 1, kBackground);
		img_.filledRectangle(0, 0, area_.x0 - 1, n_ - 1, kBackground);
		img_.filledRectangle(area_.x1 + 1, 0, n_ - 1, n_ - 1, kBackground);
		img_.rectangle(area_.x0, area_.y0, area_.x1, area_.y1, kFrameColor, 1);
	}

	void drawLegend()
	{
		const Rect& box = legend_box_;
		if (box.empty()) return;
		const Font& f = style_.body;
		const int row_h = legendRowHeight();
		img_.filledRectangle(box.x0, box.y0, box.x1, box.y1, kBackground);
		img_.rectangle(box.x0, box.y0, box.x1, box.y1, kFrameColor, 1);
		for (std::size_t i = 0; i < legend_.size(); ++i)
		{
			const int cy = box.y0 + 6 + static_cast<int>(i) * row_h + row_h / 2;
			legend_[i].glyph(img_, box.x0 + 8 + kGlyphHalf, cy);
			text(img_, box.x0 + 2 * kGlyphHalf + 16, cy - f.h / 2, legend_[i].label, f, kTextColor);
		}
	}

	/// Coordinates of the grid lines along the bottom and left edges of the
	/// plot, except where they would run into the legend.
	void drawGridLabels()
	{
		const Font& f = style_.label;
		const auto put = [&](int x, int y, double value) {
			const std::string s = mg::formatLength(std::abs(value) < 1e-9 * step_ ? 0.0 : value);
			const Rect r{x, y, x + textWidth(s, f), y + f.h};
			if (r.x0 <= area_.x0 || r.x1 >= area_.x1 || r.y0 <= area_.y0 || r.y1 >= area_.y1) return;
			if (r.intersects(legend_box_)) return;
			text(img_, x, y, s, f, kGridLabelColor);
		};
		const int x_row = area_.y1 - f.h - 3;  // the x labels' row, kept free of y labels
		for (const auto& [x, value] : x_grid_) put(x + 3, x_row, value);
		for (const auto& [y, value] : y_grid_)
			if (y - 1 < x_row) put(area_.x0 + 4, y - f.h - 1, value);
	}

	/// A bar one grid step long, under the plot at the right, labelled on its
	/// left ("10 m |-----|").
	void drawScaleBar()
	{
		const int len = PixelMap::toPixel(step_ * map_.scale());
		const int x1 = area_.x1, x0 = x1 - len, y = area_.y1 + 8 + style_.body.h / 2;
		img_.line(x0, y, x1, y, kTextColor, 2);
		img_.line(x0, y - 4, x0, y + 4, kTextColor, 2);
		img_.line(x1, y - 4, x1, y + 4, kTextColor, 2);
		const std::string label = mg::formatLength(step_);
		text(img_, x0 - 8 - textWidth(label, style_.body), y - style_.body.h / 2, label, style_.body, kTextColor);
	}

	void drawTitle()
	{
		const std::string title = run_.plugin.empty() ? std::string("esif") : run_.plugin;
		text(img_, (n_ - textWidth(title, style_.title)) / 2, 6, title, style_.title, kTextColor);
		std::string subtitle = std::filesystem::path(run_.rawlog).filename().string();
		subtitle += (subtitle.empty() ? "" : "  -  ") + std::to_string(run_.final_estimate.landmarks.size()) +
					" landmarks, " + std::to_string(run_.trajectory.size()) + " steps";
		text(img_, (n_ - textWidth(subtitle, style_.body)) / 2, 10 + style_.title.h, subtitle, style_.body,
			 kGridLabelColor);
	}

	static constexpr int kGlyphHalf = 12;  ///< half width of legend glyphs [px]

	const RunRecord& run_;
	const double sigmas_;
	const int n_;
	const Style style_;
	const Rect area_;  ///< the plot area, between the title and scale bar bands
	const std::vector<Eigen::Vector2d> traj_;
	const std::vector<Eigen::Vector2d> truth_path_;
	const std::vector<LegendEntry> legend_;
	PixelMap map_;
	Rect legend_box_;
	double step_ = 1;  ///< grid step [m]
	std::vector<std::pair<int, double>> x_grid_, y_grid_;  ///< (pixel, metres) of each grid line
	mrpt::img::CImage img_;
};
}  // namespace

void validateMapWriterOptions(const MapWriterOptions& options) { mg::validateOptions(options); }

void writeMapImage(const RunRecord& run, const std::string& path, const MapWriterOptions& options)
{
	mg::validateOptions(options);
	const mrpt::img::CImage img = MapPainter(run, options).paint();

	figure_canvas::savePngAtomically(img, path);
}

}  // namespace esif
