/// \file feature_std.cpp
/// The book's Fig. 4.9: the standard deviation of three features over time
/// for EKF SLAM, D-SLAM and the D-SLAM local map joining filter, each run
/// with its committed config (configs/ekf.ini, dslam.ini, dslam_lmj.ini).
///
/// usage: feature_std RAWLOG OUT.png [ID ID ID]
/// Without IDs it takes the first feature measured, and the features first
/// measured nearest to steps 1100 and 2000 (the book's feature 71 was first
/// seen at about step 1100). Writes OUT.png and OUT.csv (step, then one
/// column per filter and feature; empty while a filter has not mapped it).

#include "FeatureStdTrace.h"

#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/render/FigureWriter.h>
#include <esif/loader/PluginLoader.h>
#include <esif/safeio/AtomicFile.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

namespace
{
using namespace esif;

/// The plugin of a committed config, configured from its own section.
FilterPlugin::Ptr pluginOf(const std::string& config_path, PluginLoader& loader)
{
	const ConfigFile cfg = ConfigFile::load(config_path);
	auto plugin = loader.create(cfg.section("esif").getString("plugin"));
	plugin->configure(cfg.section(plugin->sectionName()));
	return plugin;
}

/// The landmark first measured nearest to `step`.
LandmarkId firstSeenNear(const Rawlog& log, std::size_t step)
{
	std::map<LandmarkId, std::size_t> first;
	for (std::size_t k = 0; k < log.steps.size(); ++k)
		if (log.steps[k].scan)
			for (const auto& m : log.steps[k].scan->measurements)
				if (m.id) first.emplace(*m.id, k);
	LandmarkId best = -1;
	std::size_t best_gap = static_cast<std::size_t>(-1);
	for (const auto& [id, k] : first)
		if (const std::size_t gap = k > step ? k - step : step - k; gap < best_gap) best = id, best_gap = gap;
	return best;
}

std::string csvOf(const std::vector<std::string>& names, const std::vector<LandmarkId>& ids,
				  const std::vector<bench::FeatureStdTrace>& traces, std::size_t steps)
{
	std::ostringstream out;
	out << "step";
	for (const auto& name : names)
		for (const LandmarkId id : ids) out << "," << name << "_" << id;
	out << "\n";
	for (std::size_t k = 0; k < steps; ++k)
	{
		out << k;
		for (const auto& trace : traces)
			for (const auto& feature : trace)
			{
				out << ",";
				if (std::isfinite(feature[k])) out << feature[k];
			}
		out << "\n";
	}
	return out.str();
}

int run(int argc, char** argv)
{
	if (argc != 3 && argc != 6)
	{
		std::cerr << "usage: feature_std RAWLOG OUT.png [ID ID ID]\n";
		return 2;
	}
	const Rawlog log = readRawlog(argv[1]);
	std::vector<LandmarkId> ids;
	if (argc == 6)
		for (int i = 3; i < 6; ++i) ids.push_back(std::stoll(argv[i]));
	else
		ids = {firstSeenNear(log, 0), firstSeenNear(log, 1100), firstSeenNear(log, 2000)};

	PluginLoader loader;
	loader.loadAll();
	const std::vector<std::string> names = {"EKF", "D-SLAM", "D-SLAM map joining"};
	std::vector<bench::FeatureStdTrace> traces;
	for (const char* config : {"configs/ekf.ini", "configs/dslam.ini", "configs/dslam_lmj.ini"})
	{
		auto plugin = pluginOf(config, loader);
		traces.push_back(bench::traceFeatureStd(*plugin, log, ids));
	}

	const auto first = bench::firstSightings(log, ids);
	LineChart chart{"standard deviation of three features (book Fig. 4.9)", "step", {}};
	for (std::size_t i = 0; i < ids.size(); ++i)
	{
		LinePanel panel{"feature " + std::to_string(ids[i]) + " (first seen at step " + std::to_string(first[i]) +
							"): sigma [m]",
						{}};
		for (std::size_t f = 0; f < names.size(); ++f)
		{
			LineSeries s{names[f], {}};
			for (std::size_t k = 0; k < log.steps.size(); ++k) s.points.emplace_back(k, traces[f][i][k]);
			panel.series.push_back(std::move(s));
		}
		chart.panels.push_back(std::move(panel));
	}
	const std::string png = argv[2];
	writeLineChartImage(chart, png, 1000);
	writeTextAtomically(png.substr(0, png.rfind('.')) + ".csv", csvOf(names, ids, traces, log.steps.size()));
	std::cout << "feature_std: " << png << " (features";
	for (const LandmarkId id : ids) std::cout << " " << id;
	std::cout << ")\n";
	return 0;
}
}  // namespace

int main(int argc, char** argv)
{
	try
	{
		return run(argc, argv);
	}
	catch (const std::exception& e)
	{
		std::cerr << "feature_std: error: " << e.what() << "\n";
		return 1;
	}
}
