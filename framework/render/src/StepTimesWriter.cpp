/// \file StepTimesWriter.cpp
/// step_times.png (book Fig. 3.20): the time of every step against the
/// landmarks mapped, with per-bin medians so that growth with map size shows.

#include <esif/render/FigureWriter.h>

#include "PlotScript.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace esif
{
namespace
{
/// The time axis ends here, so that a few slow steps (a reordering, a page
/// fault) do not squash the rest into a line at the bottom.
constexpr double kClipPercentile = 0.999;
/// About this many bins of the landmark axis carry a median.
constexpr double kTargetBins = 50;

struct StepPoint
{
	double landmarks = 0;
	double ms = 0;
};

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

/// "N steps, M above the 99.9th percentile (X ms) clipped; line: median per ..."
std::string subtitle(std::size_t steps, std::size_t clipped, double clip_ms, long long bin_width)
{
	char buf[160];
	std::snprintf(buf, sizeof buf, "%zu steps, %zu above the 99.9th percentile (%.3g ms) clipped; line: median ",
		steps, clipped, clip_ms);
	return buf + (bin_width == 1 ? std::string("per landmark count")
								 : "per bin of " + std::to_string(bin_width) + " landmark counts");
}

plot::Figure stepTimesFigure(const std::vector<StepPoint>& pts, int width_px)
{
	std::vector<double> ms;
	double x_max = 0;
	for (const StepPoint& p : pts)
	{
		ms.push_back(p.ms);
		x_max = std::max(x_max, p.landmarks);
	}
	const double clip_ms = percentile(ms, kClipPercentile);
	const auto clipped = static_cast<std::size_t>(std::count_if(ms.begin(), ms.end(), [&](double v) { return v > clip_ms; }));
	const long long width = binWidth(x_max);

	plot::Figure fig(width_px, width_px * 3 / 4);
	fig.command(plot::chartDefaults());
	fig.command("set title " + plot::twoLines(plot::withBookFigure("processing time per step vs landmarks mapped", "Fig. 3.20"),
								   subtitle(pts.size(), clipped, clip_ms, width)));
	fig.command("set xlabel 'landmarks mapped'\nset ylabel 'time per step [ms]'");
	if (pts.empty())
	{
		fig.command("set xrange [0:1]\nset yrange [0:1]\nset label 1 'no steps' at graph 0.5,0.5 center\nplot 2 notitle");
		return fig;
	}
	plot::DataBlock dots, medians;
	for (const StepPoint& p : pts) dots.row({p.landmarks, p.ms});
	for (const StepPoint& m : binMedians(pts, width)) medians.row({m.landmarks, m.ms});
	fig.command("set xrange [0:" + plot::number(std::max(1.0, x_max * 1.02)) + "]");
	fig.command("set yrange [0:" + plot::number(clip_ms > 0 ? clip_ms * 1.02 : 1.0) + "]");
	fig.command(plot::plotCommand({fig.add(dots) + " using 1:2 with points pt 5 ps 0.3 lc rgb '#7f9fd8' title 'one step'",
		fig.add(medians) + " using 1:2 with lines lw 2.5 lc rgb '#e6194b' title 'median'"}));
	return fig;
}
}  // namespace

void writeStepTimesImage(
	const std::vector<double>& step_us, const std::vector<std::size_t>& landmark_counts, const std::string& path,
	int width_px)
{
	if (step_us.size() != landmark_counts.size())
		throw std::invalid_argument(path + ": " + std::to_string(step_us.size()) + " step times but " +
									std::to_string(landmark_counts.size()) + " landmark counts");
	plot::validateWidth(width_px, "image_size_px");
	plot::writeFigure(stepTimesFigure(finitePoints(step_us, landmark_counts), width_px), path);
}

}  // namespace esif
