/// \file LineChartWriter.cpp
/// Line charts (FigureWriter.h): panels of lines and shaded bands over a
/// shared x axis, e.g. a campaign's ANEES with its chi-square bounds, and
/// localmap_times.png (book Fig. 4.20, 5.11).

#include <esif/render/FigureWriter.h>

#include "PlotScript.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace esif
{
namespace
{
/// A point a panel can show: finite, and positive on a log axis.
bool drawable(double x, double y, bool log_y) { return std::isfinite(x) && std::isfinite(y) && (!log_y || y > 0); }

/// The series' points; a point that cannot be drawn breaks the line there.
plot::DataBlock seriesBlock(const LineSeries& s, bool log_y)
{
	plot::DataBlock block;
	for (const auto& [x, y] : s.points)
		drawable(x, y, log_y) ? block.row({x, y}) : block.breakLine();
	return block;
}

/// The band's (x, lower, upper) rows; a row that cannot be drawn breaks it.
plot::DataBlock bandBlock(const ShadedBand& b, bool log_y)
{
	plot::DataBlock block;
	for (const auto& [x, lo, hi] : b.points)
		drawable(x, lo, log_y) && drawable(x, hi, log_y) ? block.row({x, lo, hi}) : block.breakLine();
	return block;
}

std::string keyTitle(const std::string& label) { return label.empty() ? "notitle" : "title " + plot::quoted(label); }

/// The plot clauses of one panel: bands first (under the lines), then lines.
std::vector<std::string> panelClauses(plot::Figure& fig, const LinePanel& panel)
{
	std::vector<std::string> clauses;
	for (const ShadedBand& b : panel.bands)
	{
		const plot::DataBlock block = bandBlock(b, panel.log_y);
		if (block.empty()) continue;
		const std::string colour =
			b.colour_of < 0 ? std::string("#c8c8c8") : plot::tint(plot::seriesColour(std::size_t(b.colour_of)), 0.7);
		clauses.push_back(fig.add(block) + " using 1:2:3 with filledcurves fc rgb '" + colour + "' " + keyTitle(b.label));
	}
	for (std::size_t i = 0; i < panel.series.size(); ++i)
	{
		const LineSeries& s = panel.series[i];
		const plot::DataBlock block = seriesBlock(s, panel.log_y);
		if (block.empty()) continue;
		const std::string colour = std::string("lc rgb '") + plot::seriesColour(i) + "'";
		const std::string style = s.markers_only ? "with points pt 7 ps 0.7 " : "with lines lw 2 ";
		clauses.push_back(fig.add(block) + " using 1:2 " + style + colour + " " + keyTitle(s.label));
	}
	return clauses;
}

/// Settings and plot command of one panel; `last` carries the x label.
void addPanel(plot::Figure& fig, const LinePanel& panel, const std::string& x_label, bool last)
{
	fig.command("set ylabel " + plot::quoted(panel.y_label));
	fig.command(last ? "set xlabel " + plot::quoted(x_label) : "unset xlabel");
	fig.command(panel.log_y ? "set logscale y\nset format y '%g'" : "unset logscale y\nset format y '%g'");
	const std::vector<std::string> clauses = panelClauses(fig, panel);
	if (clauses.empty())
	{
		// Nothing to show: an empty frame that says so rather than no panel.
		fig.command("unset logscale y\nset xrange [0:1]\nset yrange [0:1]\nset label 1 'no data' at graph 0.5,0.5 center");
		fig.command("plot 2 notitle\nunset label 1\nset yrange [*:*]");
		return;
	}
	fig.command("set xrange [0:*]\nset yrange [*:*]");
	fig.command(plot::plotCommand(clauses));
}
}  // namespace

void writeLineChartImage(const LineChart& chart, const std::string& path, int width_px)
{
	plot::validateWidth(width_px, "image_size_px");
	plot::Figure fig(width_px, width_px * 3 / 4);
	fig.command(plot::chartDefaults());
	const std::size_t n = std::max<std::size_t>(chart.panels.size(), 1);
	fig.command(plot::multiplotTitle(plot::withBookFigure(chart.title, chart.book_figure), std::to_string(n) + ",1"));
	for (std::size_t i = 0; i < chart.panels.size(); ++i)
		addPanel(fig, chart.panels[i], chart.x_label, i + 1 == chart.panels.size());
	if (chart.panels.empty()) addPanel(fig, LinePanel{}, chart.x_label, true);
	plot::writeFigure(fig, path);
}

namespace
{
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

void writeLocalMapTimesImage(const std::vector<LocalMapFusionCost>& costs, const std::string& path, int width_px)
{
	const LineChart chart{"time to fuse each local map (" + std::to_string(costs.size()) + " maps)",
		"local map k",
		{fusionPanel("fusion time [ms]", costs, [](const LocalMapFusionCost&) { return 1.0; }),
			fusionPanel("fusion time / state dimension [ms]", costs,
				[](const LocalMapFusionCost& c) { return static_cast<double>(c.state_dim); })},
		"Fig. 4.20, 5.11"};
	writeLineChartImage(chart, path, width_px);
}

}  // namespace esif
