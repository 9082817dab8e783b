/// \file FigureWriter.cpp
/// info_matrix.png (book Fig. 3.12-3.13), step_times.png (Fig. 3.20) and
/// line charts: localmap_times.png (Fig. 5.7-5.8), feature_std.png (Fig. 4.9).

#include <esif/render/FigureWriter.h>

#include "FigureCanvas.h"
#include "MapPalette.h"

#include <mrpt/img/CImage.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace esif
{
namespace
{
using namespace figure_canvas;
using Sparse = Eigen::SparseMatrix<double>;

// --- info_matrix.png ---------------------------------------------------------

constexpr int kPanelMargin = 16;  ///< white room around each panel's matrix [px]

/// Height of the title band above the matrices, the same for every panel.
int titleBandPx() { return kFontLarge.h + 2 * kPanelMargin; }

long long squareSize(const Sparse& m) { return std::max<long long>(m.rows(), m.cols()); }

/// Entries != 0 (a NaN counts: it is a non-zero gone wrong).
std::size_t nonZeroCount(const Sparse& m)
{
	std::size_t nz = 0;
	for (Eigen::Index k = 0; k < m.outerSize(); ++k)
		for (Sparse::InnerIterator it(m, k); it; ++it) nz += it.value() != 0.0;
	return nz;
}

/// The panel at position `index` (0 = left) for an n x n matrix.
MatrixPanel placePanel(int index, long long n, int size_px)
{
	const int room = std::min(size_px - 2 * kPanelMargin, size_px - titleBandPx() - kPanelMargin);
	MatrixPanel p;
	p.side_px = (n > 0 && n <= room) ? static_cast<int>(room / n * n) : room;
	p.x0 = index * size_px + (size_px - p.side_px) / 2;
	p.y0 = titleBandPx();  // right under the title; spare room goes below
	return p;
}

/// Black pixels where `m` is non-zero, following MatrixPanel's mapping.
void drawPattern(mrpt::img::CImage& img, const MatrixPanel& panel, const Sparse& m)
{
	const long long n = squareSize(m), side = panel.side_px;
	if (n == 0) return;
	const auto first = [&](long long i) { return i * side / n; };
	const auto last = [&](long long i) { return std::max(first(i), first(i + 1) - 1); };
	for (Eigen::Index k = 0; k < m.outerSize(); ++k)
		for (Sparse::InnerIterator it(m, k); it; ++it)
		{
			if (it.value() == 0.0) continue;
			for (long long y = first(it.row()); y <= last(it.row()); ++y)
				for (long long x = first(it.col()); x <= last(it.col()); ++x)
					putPixel(img, panel.x0 + static_cast<int>(x), panel.y0 + static_cast<int>(y), kInk);
		}
}

/// One panel: title centred over a grey frame around the pattern.
void drawMatrixPanel(
	mrpt::img::CImage& img, const MatrixPanel& panel, const Sparse& m, const std::string& title, int size_px)
{
	const int s = panel.side_px;
	// The frame one pixel outside the pattern, set pixel by pixel: MRPT's
	// rectangle() strokes inside its corners and would cover the first row.
	for (int t = -1; t <= s; ++t)
	{
		putPixel(img, panel.x0 + t, panel.y0 - 1, kFrameColor);
		putPixel(img, panel.x0 + t, panel.y0 + s, kFrameColor);
		putPixel(img, panel.x0 - 1, panel.y0 + t, kFrameColor);
		putPixel(img, panel.x0 + s, panel.y0 + t, kFrameColor);
	}
	drawPattern(img, panel, m);
	const Font f = fittingFont(title, size_px - 2 * kPanelMargin, {kFontLarge, kFontMedium, kFontSmall, kFontTiny});
	centredText(img, panel.x0 + s / 2, (titleBandPx() - f.h) / 2, title, f, kTextColor);
}

std::string informationTitle(const Sparse& m)
{
	return "information matrix " + std::to_string(m.rows()) + "x" + std::to_string(m.cols()) +
		   ", nz = " + std::to_string(nonZeroCount(m));
}

/// "Cholesky factor (distance reordering), nz = N"; when factor_order names
/// the factor itself ("incomplete Cholesky preconditioner, distance
/// reordering"), it leads the title instead of "Cholesky factor".
std::string factorTitle(const InformationPattern& p)
{
	const std::string nz = ", nz = " + std::to_string(nonZeroCount(p.factor));
	if (p.factor_order.find("Cholesky") != std::string::npos) return p.factor_order + nz;
	return "Cholesky factor" + (p.factor_order.empty() ? "" : " (" + p.factor_order + ")") + nz;
}

// --- step_times.png ----------------------------------------------------------

constexpr double kClipPercentile = 0.999;
constexpr double kTargetBins = 50;

struct StepPoint
{
	double landmarks;
	double ms;
};

/// Map from data [0, x_top] x [0, y_top] onto the plot rectangle; with
/// `log_y`, y from [y_bottom, y_top] on a logarithmic scale instead.
struct Axes
{
	int x0 = 0, y0 = 0, x1 = 0, y1 = 0;	 ///< plot rectangle [px], y0 at the top
	double x_top = 1, y_top = 1;
	bool log_y = false;
	double y_bottom = 1;  ///< lowest value of a log axis (> 0)
	int px(double x) const { return x0 + static_cast<int>(std::lround((x1 - x0) * x / x_top)); }
	int py(double y) const
	{
		const double f = log_y ? (std::log10(std::clamp(y, y_bottom, y_top)) - std::log10(y_bottom)) /
									 (std::log10(y_top) - std::log10(y_bottom))
							   : std::min(y, y_top) / y_top;
		return y1 - static_cast<int>(std::lround((y1 - y0) * f));
	}
	/// Whether y can be drawn (a log axis has no place for y <= 0).
	bool drawable(double y) const { return std::isfinite(y) && (!log_y || y > 0); }
};

/// Ticks of a log axis over [lo, hi]: the powers of ten inside, and 2 and 5
/// times them when fewer than three decades are spanned.
std::vector<double> logTicks(double lo, double hi)
{
	std::vector<double> ticks;
	const bool fine = std::log10(hi / lo) < 3;
	for (int e = static_cast<int>(std::floor(std::log10(lo))); e <= static_cast<int>(std::ceil(std::log10(hi))); ++e)
		for (const double m : {1.0, 2.0, 5.0})
		{
			if (m > 1 && !fine) continue;
			const double t = m * std::pow(10.0, e);
			if (t >= lo * (1 - 1e-9) && t <= hi * (1 + 1e-9)) ticks.push_back(t);
		}
	return ticks;
}

/// Fonts for a figure width: tuned at 1000 px.
struct Fonts
{
	Font title, body, label;
	explicit Fonts(int w)
		: title(w >= 600 ? kFontLarge : kFontMedium),
		  body(w >= 600 ? kFontMedium : kFontSmall),
		  label(w >= 600 ? kFontSmall : kFontTiny)
	{
	}
};

/// Grid lines, tick marks and tick labels of both axes.
void drawGridAndTicks(mrpt::img::CImage& img, const Axes& axes, const std::vector<double>& x_ticks,
					  const std::vector<double>& y_ticks, const Font& f)
{
	for (double t : x_ticks)
	{
		const int x = axes.px(t);
		img.line(x, axes.y0, x, axes.y1, kGridColor, 1);
		img.line(x, axes.y1, x, axes.y1 + 5, kInk, 1);
		centredText(img, x, axes.y1 + 8, tickLabel(t), f, kTextColor);
	}
	for (double t : y_ticks)
	{
		const int y = axes.py(t);
		img.line(axes.x0, y, axes.x1, y, kGridColor, 1);
		img.line(axes.x0 - 5, y, axes.x0, y, kInk, 1);
		const std::string s = tickLabel(t);
		text(img, axes.x0 - 8 - textWidth(s, f), y - f.h / 2, s, f, kTextColor);
	}
}

std::vector<StepPoint> finitePoints(const std::vector<double>& step_us, const std::vector<std::size_t>& counts)
{
	std::vector<StepPoint> pts;
	pts.reserve(step_us.size());
	for (std::size_t k = 0; k < step_us.size(); ++k)
		if (std::isfinite(step_us[k])) pts.push_back({static_cast<double>(counts[k]), step_us[k] / 1000.0});
	return pts;
}

/// Nearest-rank percentile (as stats.json's step_us_p99); 0 for no data.
double percentile(std::vector<double> v, double p)
{
	if (v.empty()) return 0;
	std::sort(v.begin(), v.end());
	const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(v.size())));
	return v[std::min(v.size() - 1, rank == 0 ? 0 : rank - 1)];
}

double median(std::vector<double> v)
{
	const std::size_t mid = v.size() / 2;
	std::nth_element(v.begin(), v.begin() + mid, v.end());
	if (v.size() % 2) return v[mid];
	return 0.5 * (v[mid] + *std::max_element(v.begin(), v.begin() + mid));
}

/// Whole landmark counts per bin: about kTargetBins bins over [0, x_max].
long long binWidth(double x_max) { return std::max(1LL, static_cast<long long>(std::ceil((x_max + 1) / kTargetBins))); }

/// (bin centre, median time) of every non-empty bin, left to right. Clipped
/// steps count too: a median is robust to them.
std::vector<StepPoint> binMedians(const std::vector<StepPoint>& pts, long long width)
{
	std::map<long long, std::vector<double>> bins;
	for (const StepPoint& p : pts) bins[static_cast<long long>(p.landmarks) / width].push_back(p.ms);
	std::vector<StepPoint> medians;
	for (const auto& [bin, ms] : bins) medians.push_back({bin * width + 0.5 * (width - 1), median(ms)});
	return medians;
}

/// Draws step_times.png's content; one method per layer.
class StepTimesPainter
{
   public:
	StepTimesPainter(const std::vector<StepPoint>& pts, int width_px)
		: pts_(pts), w_(width_px), h_(width_px * 3 / 4), fonts_(w_), img_(blankImage(w_, h_))
	{
		std::vector<double> ms;
		for (const StepPoint& p : pts_) ms.push_back(p.ms);
		clip_ms_ = percentile(ms, kClipPercentile);
		clipped_ = static_cast<std::size_t>(std::count_if(ms.begin(), ms.end(), [&](double v) { return v > clip_ms_; }));
		double x_max = 0;
		for (const StepPoint& p : pts_) x_max = std::max(x_max, p.landmarks);
		bin_width_ = binWidth(x_max);
		composeSubtitle();
		layoutAxes(x_max);
	}

	mrpt::img::CImage paint()
	{
		drawGridAndTicks(img_, axes_, x_ticks_, y_ticks_, fonts_.label);
		drawPoints();
		drawMedians();
		drawAxes();
		drawTitles();
		return img_;
	}

   private:
	void layoutAxes(double x_max)
	{
		const double x_step = map_geometry::niceStep(std::max(1.0, x_max), 8);
		axes_.x_top = std::max(1.0, std::ceil(std::max(1.0, x_max) / x_step) * x_step);
		axes_.y_top = clip_ms_ > 0 ? 1.05 * clip_ms_ : 1.0;
		x_ticks_ = niceTicks(axes_.x_top, 8);
		y_ticks_ = niceTicks(axes_.y_top, 6);
		int label_w = 0;
		for (double t : y_ticks_) label_w = std::max(label_w, textWidth(tickLabel(t), fonts_.label));
		const int pad = 8;
		axes_.x0 = pad + label_w + 8;
		axes_.x1 = w_ - 3 * pad;
		axes_.y0 = fonts_.title.h + static_cast<int>(subtitle_.size()) * (sub_font_.h + pad / 2) + fonts_.label.h + 4 * pad;
		axes_.y1 = h_ - (fonts_.label.h + fonts_.body.h + 4 * pad);
	}

	void drawPoints()
	{
		const int d = w_ >= 1200 ? 1 : 0;  // half size of a dot beyond its centre pixel
		for (const StepPoint& p : pts_)
		{
			if (p.ms > clip_ms_) continue;
			const int x = axes_.px(p.landmarks), y = axes_.py(p.ms);
			img_.filledRectangle(x - d, y - d, x + d + 1, y + d + 1, map_palette::kPathColor);
		}
	}

	void drawMedians()
	{
		const std::vector<StepPoint> medians = binMedians(pts_, bin_width_);
		const unsigned thick = w_ >= 600 ? 2 : 1;
		for (std::size_t i = 0; i < medians.size(); ++i)
		{
			const int x = axes_.px(medians[i].landmarks), y = axes_.py(medians[i].ms);
			const int m = thick;  // marker half size
			img_.filledRectangle(x - m, y - m, x + m, y + m, map_palette::kLandmarkColor);
			if (i > 0)
				img_.line(
					axes_.px(medians[i - 1].landmarks), axes_.py(medians[i - 1].ms), x, y, map_palette::kLandmarkColor,
					thick);
		}
	}

	void drawAxes()
	{
		img_.line(axes_.x0, axes_.y0, axes_.x0, axes_.y1, kInk, 1);
		img_.line(axes_.x0, axes_.y1, axes_.x1, axes_.y1, kInk, 1);
	}

	void drawTitles()
	{
		const int pad = 8;
		const std::string title = "processing time per step vs landmarks mapped";
		centredText(img_, w_ / 2, pad, title, fittingFont(title, w_ - 2 * pad, {fonts_.title, kFontSmall, kFontTiny}),
					kTextColor);
		for (std::size_t i = 0; i < subtitle_.size(); ++i)
			centredText(img_, w_ / 2, 2 * pad + fonts_.title.h + static_cast<int>(i) * (sub_font_.h + pad / 2),
						subtitle_[i], sub_font_, kMutedTextColor);
		text(img_, pad, axes_.y0 - fonts_.label.h - pad, "time per step [ms]", fonts_.label, kTextColor);
		centredText(img_, (axes_.x0 + axes_.x1) / 2, h_ - fonts_.body.h - pad, "landmarks mapped", fonts_.body,
					kTextColor);
	}

	/// What is clipped and what the red line is, in the body font on one
	/// line when it fits, else wrapped in a smaller font.
	void composeSubtitle()
	{
		char clip[160];
		std::snprintf(
			clip, sizeof(clip), "%zu steps, %zu above the 99.9th percentile (%.3g ms) clipped", pts_.size(), clipped_,
			clip_ms_);
		const std::string median =
			bin_width_ == 1 ? "per landmark count" : "per bin of " + std::to_string(bin_width_) + " landmark counts";
		const std::string sub = std::string(clip) + "; red: median " + median;
		const int room = w_ - 16;
		sub_font_ = textWidth(sub, fonts_.body) <= room ? fonts_.body : (w_ >= 400 ? kFontSmall : kFontTiny);
		subtitle_ = wrapText(sub, sub_font_, room);
	}

	const std::vector<StepPoint>& pts_;
	const int w_, h_;
	const Fonts fonts_;
	mrpt::img::CImage img_;
	double clip_ms_ = 0;
	std::size_t clipped_ = 0;
	long long bin_width_ = 1;
	Axes axes_;
	std::vector<double> x_ticks_, y_ticks_;
	std::vector<std::string> subtitle_;
	Font sub_font_ = kFontTiny;
};

// --- line charts (localmap_times.png, feature_std.png) -----------------------

/// Colours of a chart's series, in order.
const TColor kSeriesColors[] = {map_palette::kLandmarkColor, map_palette::kPathColor,
								map_palette::kTruthLandmarkColor, TColor(200, 130, 0), TColor(120, 50, 170)};

TColor seriesColor(std::size_t i) { return kSeriesColors[i % (sizeof(kSeriesColors) / sizeof(kSeriesColors[0]))]; }

/// Draws a LineChart: its panels one above the other over a shared x
/// range, each a line chart of its series with a legend in the corner.
class LineChartPainter
{
   public:
	LineChartPainter(const LineChart& chart, int width_px)
		: chart_(chart), w_(width_px), h_(width_px * 3 / 4), fonts_(w_), img_(blankImage(w_, h_))
	{
		for (const auto& panel : chart_.panels)
		{
			for (const auto& s : panel.series)
				for (const auto& [x, y] : s.points)
					if (std::isfinite(x)) x_max_ = std::max(x_max_, x);
			for (const auto& b : panel.bands)
				for (const auto& p : b.points)
					if (std::isfinite(p[0])) x_max_ = std::max(x_max_, p[0]);
		}
	}

	mrpt::img::CImage paint()
	{
		const int pad = 8;
		centredText(img_, w_ / 2, pad, chart_.title,
					fittingFont(chart_.title, w_ - 2 * pad, {fonts_.title, kFontSmall, kFontTiny}), kTextColor);
		const int top = 2 * pad + fonts_.title.h, bottom = h_ - (fonts_.body.h + 2 * pad);
		const int n = std::max<int>(1, static_cast<int>(chart_.panels.size()));
		for (int i = 0; i < static_cast<int>(chart_.panels.size()); ++i)
			drawPanel(top + (bottom - top) * i / n, top + (bottom - top) * (i + 1) / n, chart_.panels[i]);
		centredText(img_, w_ / 2, h_ - fonts_.body.h - pad, chart_.x_label, fonts_.body, kTextColor);
		return img_;
	}

   private:
	/// One panel in the band [y_top, y_bottom): y label above the plot,
	/// ticks on both axes, the series as lines with a legend top-right.
	void drawPanel(int y_top, int y_bottom, const LinePanel& panel)
	{
		const int pad = 8;
		Axes axes;
		const double x_step = map_geometry::niceStep(x_max_, 8);
		axes.x_top = std::ceil(x_max_ / x_step) * x_step;
		const std::vector<double> x_ticks = niceTicks(axes.x_top, 8);
		const std::vector<double> y_ticks = layoutYAxis(panel, axes);
		int label_w = 0;
		for (double t : y_ticks) label_w = std::max(label_w, textWidth(tickLabel(t), fonts_.label));
		axes.x0 = pad + label_w + 8;
		axes.x1 = w_ - 3 * pad;
		axes.y0 = y_top + fonts_.label.h + 2 * pad;
		axes.y1 = y_bottom - (fonts_.label.h + 2 * pad);
		drawGridAndTicks(img_, axes, x_ticks, y_ticks, fonts_.label);
		for (const auto& band : panel.bands) drawBand(axes, band);
		// Last series first, so the first shows where they coincide.
		for (std::size_t i = panel.series.size(); i-- > 0;) drawSeries(axes, panel.series[i], seriesColor(i));
		img_.line(axes.x0, axes.y0, axes.x0, axes.y1, kInk, 1);
		img_.line(axes.x0, axes.y1, axes.x1, axes.y1, kInk, 1);
		text(img_, pad, y_top + pad / 2, panel.y_label, fonts_.label, kTextColor);
		drawLegend(axes.x1, y_top + pad / 2, panel);
	}

	/// The y range (linear from 0, or log over the positive values) and its ticks.
	static std::vector<double> layoutYAxis(const LinePanel& panel, Axes& axes)
	{
		double y_min = std::numeric_limits<double>::infinity(), y_max = 0;
		const auto include = [&](double y) {
			if (!std::isfinite(y) || (panel.log_y && y <= 0)) return;
			y_min = std::min(y_min, y);
			y_max = std::max(y_max, y);
		};
		for (const auto& s : panel.series)
			for (const auto& [x, y] : s.points) include(y);
		for (const auto& b : panel.bands)
			for (const auto& p : b.points) include(p[1]), include(p[2]);
		if (!panel.log_y)
		{
			axes.y_top = y_max > 0 ? 1.05 * y_max : 1.0;
			return niceTicks(axes.y_top, 4);
		}
		axes.log_y = true;
		if (!(y_max > 0)) y_min = 0.1, y_max = 10;
		// At least a factor 10 shown, with a margin of 10 % of a decade each side.
		axes.y_bottom = std::min(y_min, y_max / 10) / std::pow(10.0, 0.1);
		axes.y_top = y_max * std::pow(10.0, 0.1);
		return logTicks(axes.y_bottom, axes.y_top);
	}

	/// Fills between the band's curves, one pixel column at a time, with
	/// the bounds interpolated linearly in x between its points.
	void drawBand(const Axes& axes, const ShadedBand& band)
	{
		const TColor tint = bandColour(band.colour_of);
		for (std::size_t i = 1; i < band.points.size(); ++i)
		{
			const auto& a = band.points[i - 1];
			const auto& b = band.points[i];
			if (!axes.drawable(a[1]) || !axes.drawable(a[2]) || !axes.drawable(b[1]) || !axes.drawable(b[2]) ||
				!std::isfinite(a[0]) || !std::isfinite(b[0]))
				continue;
			const int xa = axes.px(a[0]), xb = axes.px(b[0]);
			for (int x = xa; x <= xb; ++x)
			{
				const double t = xb > xa ? double(x - xa) / double(xb - xa) : 0.0;
				const int lo = axes.py(a[1] + t * (b[1] - a[1])), hi = axes.py(a[2] + t * (b[2] - a[2]));
				img_.line(x, lo, x, hi, tint, 1);
			}
		}
	}

	/// A light tint of series `i`'s colour (a quarter of it on white), or light grey.
	static TColor bandColour(int i)
	{
		if (i < 0) return TColor(215, 215, 215);
		const TColor c = seriesColor(static_cast<std::size_t>(i));
		const auto tint = [](int v) { return static_cast<uint8_t>(255 - (255 - v) / 4); };
		return TColor(tint(c.R), tint(c.G), tint(c.B));
	}

	/// A polyline through the finite points; a gap where a point is not finite.
	void drawSeries(const Axes& axes, const LineSeries& s, TColor color)
	{
		const unsigned thick = w_ >= 600 ? 2 : 1;
		bool have_previous = false;
		int px = 0, py = 0;
		for (const auto& [x, y] : s.points)
		{
			if (!std::isfinite(x) || !axes.drawable(y))
			{
				have_previous = false;
				continue;
			}
			const int cx = axes.px(x), cy = axes.py(y);
			if (s.markers_only)
				img_.filledRectangle(cx - 2, cy - 2, cx + 2, cy + 2, color);
			else if (have_previous)
				img_.line(px, py, cx, cy, color, thick);
			else
				img_.filledRectangle(cx - 1, cy - 1, cx + 1, cy + 1, color);
			px = cx, py = cy, have_previous = true;
		}
	}

	/// The legend on one line above the plot, ending at `right`: a short
	/// line in each series' colour before its label, then a swatch before
	/// each labelled band's.
	void drawLegend(int right, int y, const LinePanel& panel)
	{
		const Font& f = fonts_.label;
		constexpr int kGlyph = 24, kGap = 6, kSpacing = 18;
		int width = 0;
		for (const auto& s : panel.series) width += kGlyph + kGap + textWidth(s.label, f) + kSpacing;
		for (const auto& b : panel.bands)
			if (!b.label.empty()) width += kGlyph + kGap + textWidth(b.label, f) + kSpacing;
		int x = right - width + kSpacing;
		for (std::size_t i = 0; i < panel.series.size(); ++i)
		{
			const int mid = x + kGlyph / 2, cy = y + f.h / 2;
			if (panel.series[i].markers_only)
				img_.filledRectangle(mid - 2, cy - 2, mid + 2, cy + 2, seriesColor(i));
			else
				img_.line(x, cy, x + kGlyph, cy, seriesColor(i), 2);
			text(img_, x + kGlyph + kGap, y, panel.series[i].label, f, kTextColor);
			x += kGlyph + kGap + textWidth(panel.series[i].label, f) + kSpacing;
		}
		for (const auto& b : panel.bands)
		{
			if (b.label.empty()) continue;
			img_.filledRectangle(x, y + 1, x + kGlyph, y + f.h - 2, bandColour(b.colour_of));
			text(img_, x + kGlyph + kGap, y, b.label, f, kTextColor);
			x += kGlyph + kGap + textWidth(b.label, f) + kSpacing;
		}
	}

	const LineChart& chart_;
	const int w_, h_;
	const Fonts fonts_;
	mrpt::img::CImage img_;
	double x_max_ = 1;
};

/// The two series of a panel of localmap_times.png: the whole fusion and
/// the fusion without data association, each divided by `divide(cost)`.
template <class Divisor>
LinePanel fusionPanel(const std::string& y_label, const std::vector<LocalMapFusionCost>& costs, Divisor divide)
{
	LinePanel panel{y_label, {{"with association", {}}, {"without association", {}}}};
	for (const auto& c : costs)
	{
		const double d = divide(c);
		const double k = static_cast<double>(c.map);
		if (!(d > 0) || !std::isfinite(c.total_s)) continue;
		panel.series[0].points.emplace_back(k, 1000.0 * c.total_s / d);
		panel.series[1].points.emplace_back(k, 1000.0 * std::max(0.0, c.total_s - c.association_s) / d);
	}
	return panel;
}

}  // namespace

std::vector<MatrixPanel> informationPatternPanels(const InformationPattern& p, int size_px)
{
	validateSize("image_size_px", size_px);
	std::vector<MatrixPanel> panels{placePanel(0, squareSize(p.information), size_px)};
	if (p.factor.size() > 0) panels.push_back(placePanel(1, squareSize(p.factor), size_px));
	return panels;
}

void writeInformationPatternImage(const InformationPattern& p, const std::string& path, int size_px)
{
	const std::vector<MatrixPanel> panels = informationPatternPanels(p, size_px);
	mrpt::img::CImage img = blankImage(static_cast<int>(panels.size()) * size_px, size_px);
	drawMatrixPanel(img, panels[0], p.information, informationTitle(p.information), size_px);
	if (panels.size() > 1) drawMatrixPanel(img, panels[1], p.factor, factorTitle(p), size_px);
	savePngAtomically(img, path);
}

void writeStepTimesImage(
	const std::vector<double>& step_us, const std::vector<std::size_t>& landmark_counts, const std::string& path,
	int width_px)
{
	if (step_us.size() != landmark_counts.size())
		throw std::invalid_argument(
			path + ": " + std::to_string(step_us.size()) + " step times but " +
			std::to_string(landmark_counts.size()) + " landmark counts");
	validateSize("image_size_px", width_px);
	const std::vector<StepPoint> pts = finitePoints(step_us, landmark_counts);
	savePngAtomically(StepTimesPainter(pts, width_px).paint(), path);
}

void writeLineChartImage(const LineChart& chart, const std::string& path, int width_px)
{
	validateSize("image_size_px", width_px);
	savePngAtomically(LineChartPainter(chart, width_px).paint(), path);
}

void writeLocalMapTimesImage(const std::vector<LocalMapFusionCost>& costs, const std::string& path, int width_px)
{
	const LineChart chart{
		"time to fuse each local map (" + std::to_string(costs.size()) + " maps)",
		"local map k",
		{fusionPanel("fusion time [ms]", costs, [](const LocalMapFusionCost&) { return 1.0; }),
		 fusionPanel("fusion time / state dimension [ms]", costs,
					 [](const LocalMapFusionCost& c) { return static_cast<double>(c.state_dim); })}};
	writeLineChartImage(chart, path, width_px);
}

}  // namespace esif
