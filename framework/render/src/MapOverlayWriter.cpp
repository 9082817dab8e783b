/// \file MapOverlayWriter.cpp
/// maps_overlay.png (see MapOverlay.h).

#include <esif/render/MapOverlay.h>

#include "FigureCanvas.h"
#include "MapGeometry.h"
#include "MapPalette.h"

#include <algorithm>
#include <cmath>

namespace esif
{
namespace
{
using namespace figure_canvas;
namespace mg = map_geometry;

/// Colours of the layers after the reference, in order (as the line charts').
const TColor kLayerColors[] = {map_palette::kLandmarkColor, map_palette::kPathColor, map_palette::kTruthLandmarkColor,
							   TColor(200, 130, 0), TColor(120, 50, 170), TColor(0, 160, 170)};
const TColor kReferenceColor(0, 0, 0);

TColor layerColor(std::size_t i)
{
	if (i == 0) return kReferenceColor;
	return kLayerColors[(i - 1) % (sizeof(kLayerColors) / sizeof(kLayerColors[0]))];
}

std::vector<Eigen::Vector2d> pathOf(const RunOutputs& run)
{
	std::vector<Eigen::Vector2d> pts;
	pts.reserve(run.trajectory.size());
	for (const auto& p : run.trajectory) pts.emplace_back(p.pose.x, p.pose.y);
	return pts;
}

/// World to pixel with one scale on both axes, the world box centred in the plot rectangle.
class Frame
{
   public:
	Frame(const mg::Bounds& world, int x0, int y0, int x1, int y1)
		: world_(world), x0_(x0), y0_(y0), x1_(x1), y1_(y1)
	{
		scale_ = std::min((x1 - x0) / world.width(), (y1 - y0) / world.height());
		cx_ = 0.5 * (world.x_min + world.x_max);
		cy_ = 0.5 * (world.y_min + world.y_max);
	}
	double px(double x) const { return 0.5 * (x0_ + x1_) + (x - cx_) * scale_; }
	double py(double y) const { return 0.5 * (y0_ + y1_) - (y - cy_) * scale_; }
	bool inside(double px, double py) const { return px >= x0_ && px <= x1_ && py >= y0_ && py <= y1_; }
	double scale() const { return scale_; }
	int x0() const { return x0_; }
	int y0() const { return y0_; }
	int x1() const { return x1_; }
	int y1() const { return y1_; }
	/// The world coordinates at the plot's edges.
	double worldX(double px) const { return cx_ + (px - 0.5 * (x0_ + x1_)) / scale_; }
	double worldY(double py) const { return cy_ - (py - 0.5 * (y0_ + y1_)) / scale_; }

   private:
	mg::Bounds world_;
	int x0_, y0_, x1_, y1_;
	double scale_ = 1, cx_ = 0, cy_ = 0;
};

/// Grid lines every nice step with metre labels on the left and bottom edges.
void drawGrid(mrpt::img::CImage& img, const Frame& f, const Font& font)
{
	const double step = mg::niceStep(std::max(f.worldX(f.x1()) - f.worldX(f.x0()), 1e-9), 8);
	for (double x = std::ceil(f.worldX(f.x0()) / step) * step; x <= f.worldX(f.x1()); x += step)
	{
		const int px = static_cast<int>(std::lround(f.px(x)));
		img.line(px, f.y0(), px, f.y1(), kGridColor, 1);
		centredText(img, px, f.y1() + 6, tickLabel(x), font, kTextColor);
	}
	for (double y = std::ceil(f.worldY(f.y1()) / step) * step; y <= f.worldY(f.y0()); y += step)
	{
		const int py = static_cast<int>(std::lround(f.py(y)));
		img.line(f.x0(), py, f.x1(), py, kGridColor, 1);
		const std::string s = tickLabel(y);
		text(img, f.x0() - 6 - textWidth(s, font), py - font.h / 2, s, font, kTextColor);
	}
	img.rectangle(f.x0(), f.y0(), f.x1(), f.y1(), kFrameColor, 1);
}

/// A segment clipped to the plot by dropping it when either end is outside
/// (paths are dense, so nothing visible is lost at this resolution).
void drawPath(mrpt::img::CImage& img, const Frame& f, const std::vector<Eigen::Vector2d>& pts, const TColor& c,
			  unsigned width)
{
	const auto keep = mg::simplifiedIndices(pts, 0.5 / f.scale(), 20000);
	for (std::size_t k = 1; k < keep.size(); ++k)
	{
		const auto& a = pts[keep[k - 1]];
		const auto& b = pts[keep[k]];
		const double ax = f.px(a.x()), ay = f.py(a.y()), bx = f.px(b.x()), by = f.py(b.y());
		if (!f.inside(ax, ay) || !f.inside(bx, by)) continue;
		img.line(static_cast<int>(std::lround(ax)), static_cast<int>(std::lround(ay)),
				 static_cast<int>(std::lround(bx)), static_cast<int>(std::lround(by)), c, width);
	}
}

void drawLandmarks(mrpt::img::CImage& img, const Frame& f, const RunOutputs& run, bool reference,
				   const TColor& c, int mark)
{
	for (const auto& lm : run.landmarks)
	{
		if (!mg::isFinite(lm.mean)) continue;
		const double x = f.px(lm.mean.x()), y = f.py(lm.mean.y());
		if (!f.inside(x, y)) continue;
		const int ix = static_cast<int>(std::lround(x)), iy = static_cast<int>(std::lround(y));
		if (reference) img.drawCircle(ix, iy, mark + 1, c, 1);
		else
		{
			img.line(ix - mark, iy, ix + mark, iy, c, 1);
			img.line(ix, iy - mark, ix, iy + mark, c, 1);
		}
	}
}

/// Legend in the plot's top-left corner: a colour swatch and label per layer.
void drawLegend(mrpt::img::CImage& img, const Frame& f, const std::vector<MapOverlayLayer>& layers, const Font& font)
{
	int w = 0;
	for (const auto& l : layers) w = std::max(w, textWidth(l.label, font));
	const int row = font.h + 4, x = f.x0() + 8, y = f.y0() + 8;
	img.filledRectangle(x, y, x + w + 34, y + row * static_cast<int>(layers.size()) + 6, kBackground);
	img.rectangle(x, y, x + w + 34, y + row * static_cast<int>(layers.size()) + 6, kFrameColor, 1);
	for (std::size_t i = 0; i < layers.size(); ++i)
	{
		const int ly = y + 4 + static_cast<int>(i) * row;
		img.line(x + 6, ly + font.h / 2, x + 24, ly + font.h / 2, layerColor(i), 3);
		text(img, x + 30, ly, layers[i].label + (i == 0 ? " (reference)" : ""), font, kTextColor);
	}
}
}  // namespace

void writeMapOverlayImage(
	const std::vector<MapOverlayLayer>& layers, const std::string& title, const std::string& path, int width_px)
{
	validateSize("maps_overlay width", width_px);
	if (layers.empty()) throw ConfigError("maps_overlay: no run to draw");
	const int height_px = width_px * 3 / 4;
	const Font title_font = width_px >= 600 ? kFontLarge : kFontMedium;
	const Font label_font = width_px >= 600 ? kFontSmall : kFontTiny;

	mg::Bounds box;
	for (const auto& p : pathOf(layers[0].outputs)) box.add(p);
	for (const auto& lm : layers[0].outputs.landmarks) box.add(lm.mean);
	const mg::Bounds world = box.padded(1.0, 0.2);

	auto img = blankImage(width_px, height_px);
	centredText(img, width_px / 2, 8, title, fittingFont(title, width_px - 20, {title_font, kFontSmall}), kTextColor);
	const int left = 10 + 8 * label_font.w, bottom = height_px - 12 - label_font.h;
	const Frame frame(world, left, 16 + title_font.h, width_px - 16, bottom);
	drawGrid(img, frame, label_font);
	const int mark = std::max(2, width_px / 400);
	// Runs first, the reference last so that it stays visible on top.
	for (std::size_t i = layers.size(); i-- > 0;)
	{
		drawPath(img, frame, pathOf(layers[i].outputs), layerColor(i), i == 0 ? 2u : 1u);
		drawLandmarks(img, frame, layers[i].outputs, i == 0, layerColor(i), mark);
	}
	drawLegend(img, frame, layers, label_font);
	savePngAtomically(img, path);
}

}  // namespace esif
