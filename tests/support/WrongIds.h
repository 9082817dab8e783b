#pragma once
/// \file WrongIds.h
/// Misread landmark IDs for the ID-gate tests: a copy of a rawlog whose
/// measurements are in part given another ID, with the IDs stored in the
/// file (Rawlog::true_ids) kept as the truth the audit scores against.

#include <esif/formats/RawlogReader.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace esif::test
{
/// Where a measurement is: (step, index in the scan).
using MeasurementAt = std::pair<std::size_t, std::size_t>;

/// Gives `fraction` of the measurements of `log` an ID other than their own,
/// drawn uniformly from the IDs the log contains (a misread can name any
/// beacon, also one not yet mapped), with a fixed-seed RNG. Returns the
/// corrupted measurements.
inline std::vector<MeasurementAt> corruptIds(Rawlog& log, double fraction, unsigned seed)
{
	std::vector<MeasurementAt> all;
	std::set<LandmarkId> id_set;
	for (std::size_t k = 0; k < log.steps.size(); ++k)
		if (log.steps[k].scan)
			for (std::size_t i = 0; i < log.steps[k].scan->measurements.size(); ++i)
			{
				all.emplace_back(k, i);
				id_set.insert(*log.steps[k].scan->measurements[i].id);
			}
	const std::vector<LandmarkId> ids(id_set.begin(), id_set.end());
	std::mt19937 rng(seed);
	std::shuffle(all.begin(), all.end(), rng);
	all.resize(static_cast<std::size_t>(fraction * static_cast<double>(all.size()) + 0.5));
	std::uniform_int_distribution<std::size_t> pick(0, ids.size() - 1);
	for (const auto& [k, i] : all)
	{
		auto& id = log.steps[k].scan->measurements[i].id;
		LandmarkId wrong = *id;
		while (wrong == *id) wrong = ids[pick(rng)];
		id = wrong;
	}
	return all;
}

}  // namespace esif::test
