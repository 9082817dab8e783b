#pragma once
/// \file MonteCarloTables.h
/// The tables of a Monte Carlo campaign (esif montecarlo): summary.csv and
/// summary.md (one row per config), per_step.csv (ANEES, bounds and RMSE of
/// every config at every step) and landmarks.csv (final ANEES and RMSE of
/// every landmark). Numbers in CSV files at full precision, in Markdown rounded.

#include <esif/eval/MonteCarloStatistics.h>

#include <string>
#include <vector>

namespace esif
{
/// What did not finish: one line each, e.g. "ekf/seed_0007: failed (exit 3):
/// esif: numerical failure: ..." or "ekf/seed_0008: not finished".
struct CampaignGaps
{
	std::vector<std::string> failed;
	std::vector<std::string> pending;
	std::vector<std::string> suspect;  ///< finished and aggregated, but suspect (SuspectResult.h)
	std::size_t planned = 0;  ///< runs per config in the plan
};

std::string monteCarloSummaryCsv(const std::vector<ConfigStatistics>& configs, std::size_t planned);
/// summary.md's table: one row per config, one cell per column of
/// monteCarloSummaryColumns() (ColumnMeanings.h), numbers rounded.
std::vector<std::vector<std::string>> monteCarloSummaryCells(const std::vector<ConfigStatistics>& configs);

/// The title, the table, each column explained (monteCarloSummaryColumns),
/// then the runs not aggregated and the suspect ones.
std::string monteCarloSummaryMarkdown(
	const std::string& title, const std::vector<ConfigStatistics>& configs, const CampaignGaps& gaps);
/// "Runs are independent noise draws ...": the line under summary.md's legend.
const std::string& monteCarloCampaignNote();

std::string monteCarloPerStepCsv(const std::vector<ConfigStatistics>& configs);
std::string monteCarloLandmarksCsv(const std::vector<ConfigStatistics>& configs);

}  // namespace esif
