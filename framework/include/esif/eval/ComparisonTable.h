#pragma once
/// \file ComparisonTable.h
/// Side-by-side tables of several runs' stats: text for the terminal,
/// comparison.csv (one row per run, the stats.json keys as columns) and
/// comparison.md.

#include <esif/io/StatsJson.h>

#include <string>
#include <vector>

namespace esif
{
/// The keys shown in the terminal and Markdown tables, in order; the tables
/// add local_maps, join_us_mean and join_us_max (map-joining runs),
/// baselineRatioKeys() (base_*, BaselineComparison.h), runDifferenceKeys()
/// (ref_*, RunDifference.h) and referenceResultKeys() (refres_*,
/// ReferenceResultDifference.h) after them when a run has those keys.
const std::vector<std::string>& comparisonKeys();

std::string comparisonText(const std::vector<Stats>& runs);
std::string comparisonMarkdown(const std::vector<Stats>& runs);
std::string comparisonCsv(const std::vector<Stats>& runs);

}  // namespace esif
