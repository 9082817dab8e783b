#pragma once
/// \file FeatureStdTrace.h
/// The standard deviation of a few landmarks after every step of a replay,
/// for the book's Fig. 4.9 (EKF, D-SLAM and the D-SLAM map-joining filter on
/// the 196-feature simulation): sigma = sqrt(trace(P) / 2), the RMS of the
/// x and y standard deviations; NaN while a filter has not mapped the
/// landmark (the map-joining filter maps a feature only when its local map
/// is fused). Header-only, shared by bench/feature_std.cpp and the tests.

#include <esif/formats/RawlogReader.h>
#include <esif/plugin/FilterPlugin.h>

#include <cmath>
#include <map>
#include <vector>

namespace esif::bench
{
/// sigma[i][k]: landmark ids[i] after step k.
using FeatureStdTrace = std::vector<std::vector<double>>;

inline FeatureStdTrace traceFeatureStd(FilterPlugin& plugin, const Rawlog& log, const std::vector<LandmarkId>& ids)
{
	FeatureStdTrace sigma(ids.size(), std::vector<double>(log.steps.size(), NAN));
	for (std::size_t k = 0; k < log.steps.size(); ++k)
	{
		plugin.processStep(log.steps[k]);
		if (k + 1 == log.steps.size()) plugin.finish();	 // the last local map is fused at the end
		std::map<LandmarkId, double> mapped;
		for (const auto& lm : plugin.estimate().landmarks) mapped[lm.id] = std::sqrt(0.5 * lm.cov.trace());
		for (std::size_t i = 0; i < ids.size(); ++i)
			if (const auto it = mapped.find(ids[i]); it != mapped.end()) sigma[i][k] = it->second;
	}
	return sigma;
}

/// The first step at which each landmark of `ids` is measured.
inline std::vector<std::size_t> firstSightings(const Rawlog& log, const std::vector<LandmarkId>& ids)
{
	std::vector<std::size_t> first(ids.size(), log.steps.size());
	for (std::size_t k = 0; k < log.steps.size(); ++k)
		if (log.steps[k].scan)
			for (const auto& m : log.steps[k].scan->measurements)
				for (std::size_t i = 0; i < ids.size(); ++i)
					if (m.id && *m.id == ids[i] && first[i] == log.steps.size()) first[i] = k;
	return first;
}

}  // namespace esif::bench
