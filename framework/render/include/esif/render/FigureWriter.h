#pragma once
/// \file FigureWriter.h
/// Figures of a run's cost drawn by the host, whatever the plugin:
/// info_matrix.png (the book's Fig. 3.12-3.13: where the information matrix
/// and its Cholesky factor are non-zero) and step_times.png (Fig. 3.20:
/// processing time of each step against the number of landmarks mapped),
/// and for the map-joining filters localmap_times.png (Fig. 4.20, 5.11: the
/// time to fuse each local map), plus the line charts of campaigns.
///
/// gnuplot draws them all (its cairo terminals; Debian's gnuplot-nox): every
/// figure is written as the PNG named and, beside it, the same figure as an
/// SVG for papers and the web (the path with ".svg"), both atomically. Each title names
/// the book figure it corresponds to. A missing or failing gnuplot is an
/// InputError naming the PNG.

#include <esif/core/InformationPattern.h>
#include <esif/plugin/LocalMapJoiner.h>

#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace esif
{
/// Writes a PNG (and its SVG), size_px high and size_px wide per panel, with
/// the non-zeros (entries != 0; NaN counts) of `p.information` and, beside
/// it, of `p.factor` in black on white (a matrix larger than size_px / 6 is
/// shown in that many cells a side, black where any entry of the cell is
/// non-zero), each panel titled with its name, size and
/// non-zero count, e.g. "information matrix 1176x1176, nz = 44692" and
/// "Cholesky factor (distance reordering), nz = 128043" (when factor_order
/// itself names the factor, e.g. "incomplete Cholesky preconditioner,
/// distance reordering", it is the factor's title). A matrix that is not
/// square is drawn in the square of its larger dimension.
/// Throws ConfigError for size_px outside [200, 16384] before writing, and
/// InputError naming `path` when it cannot be written (nothing is left behind).
void writeInformationPatternImage(const InformationPattern& p, const std::string& path, int size_px);

/// Writes a PNG, width_px wide and 3/4 of that high, with one dot per step
/// at (landmark_counts[k], step_us[k] in ms) on linear axes from 0 with round
/// ticks, and the median time of the steps in each of about 50 bins of the
/// landmark axis as a line, so that growth with map size shows. The time
/// axis ends at the 99.9th percentile (nearest rank) of the times; the title
/// says how many steps above it are clipped (not drawn). Non-finite times
/// are left out. Throws std::invalid_argument when the two vectors differ in
/// length, ConfigError for width_px outside [200, 16384] (both before
/// writing), and InputError naming `path` when it cannot be written.
void writeStepTimesImage(
	const std::vector<double>& step_us, const std::vector<std::size_t>& landmark_counts, const std::string& path,
	int width_px);

/// One line of a chart: (x, y) points, joined in order; a non-finite point
/// (or, on a log axis, one <= 0) breaks the line. With `markers_only`, a
/// dot per point and no line (values that are not a sequence, e.g. one per
/// landmark).
struct LineSeries
{
	std::string label;
	std::vector<std::pair<double, double>> points;
	bool markers_only = false;
};

/// A shaded region between two curves, e.g. the chi-square bounds of an
/// ANEES or the spread of an error over runs: (x, lower, upper) points,
/// filled between consecutive points. Drawn under the lines, in a light
/// tint of series `colour_of`'s colour, or light grey when it is -1.
struct ShadedBand
{
	std::string label;	///< in the legend; empty: not listed
	std::vector<std::array<double, 3>> points;
	int colour_of = -1;
};

/// One panel: its y-axis label and its lines (coloured in order from
/// twelve distinct colours), with optional shaded bands under them and a
/// logarithmic y axis (the range spans the positive values of lines and
/// bands).
struct LinePanel
{
	std::string y_label;
	std::vector<LineSeries> series;
	std::vector<ShadedBand> bands = {};
	bool log_y = false;
};

/// Panels one above the other over a shared x axis from 0.
struct LineChart
{
	std::string title;
	std::string x_label;
	std::vector<LinePanel> panels;
	std::string book_figure = {};  ///< e.g. "Fig. 3.15": added to the title
};

/// Writes `chart` as a PNG, width_px wide and 3/4 of that high, each panel
/// with ticks, grid and a legend. Throws ConfigError for width_px outside
/// [200, 16384] before writing, and InputError naming `path` when it cannot
/// be written.
void writeLineChartImage(const LineChart& chart, const std::string& path, int width_px);

/// Writes a PNG, width_px wide and 3/4 of that high, with two panels
/// against the map index k (book Fig. 5.7-5.8): the time to fuse each map
/// [ms], and that time divided by the global state dimension after the
/// fusion; each with two lines, the whole fusion ("with association") and
/// the fusion minus its data association ("without association"). Maps with
/// a non-finite time or a zero state dimension are left out of the panel
/// that cannot show them. Throws ConfigError for width_px outside [200,
/// 16384] before writing, and InputError naming `path` when it cannot be
/// written.
void writeLocalMapTimesImage(const std::vector<LocalMapFusionCost>& costs, const std::string& path, int width_px);

}  // namespace esif
