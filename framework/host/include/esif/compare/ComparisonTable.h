#pragma once
/// \file ComparisonTable.h
/// Side-by-side tables of several runs' stats: text for the terminal,
/// comparison.csv (one row per run, the stats.json keys as columns) and
/// comparison.md.

#include <esif/formats/StatsJson.h>

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

/// The row of a run that failed: label, plugin, status "failed", exit_code
/// (the `esif run` child's) and error (the first error line of its stderr).
/// The tables show status and exit_code after plugin, the CSV every key.
Stats failedRunStats(const std::string& label, const std::string& plugin, int exit_code, const std::string& error);

/// The row of a run that was not started (status "not run", exit_code null)
/// because `reason` (e.g. the run whose data association it reuses failed).
Stats notRunStats(const std::string& label, const std::string& plugin, const std::string& reason);

/// Whether the row is a failed or a not-run one.
bool isFailedRun(const Stats& run);

/// When any row failed or is suspect (SuspectResult.h), gives the others
/// status "ok" or "suspect", so the status column is complete; otherwise
/// leaves every row as it is (no status column).
void markSucceededRuns(std::vector<Stats>& runs);

/// One line per failed, not-run or suspect row: "run 'LABEL' failed (exit
/// N): ERROR", "run 'LABEL' not run: REASON" or "run 'LABEL' is suspect:
/// REASON"; empty when every run succeeded and none is suspect.
std::string failureNote(const std::vector<Stats>& runs);

/// `esif compare`'s exit code: 0 when no run failed, else the exit code of
/// the first failed run in the order of the rows (the order of --configs),
/// so a lone failure keeps its child's code (3 stays 3). Not-run rows do
/// not count: the run they depend on failed before them.
int comparisonExitCode(const std::vector<Stats>& runs);

/// The table the terminal, comparison.md and comparison.html show: one
/// column per run (labels), one row per key (tableKeys), cells[row][run]
/// with numbers to 4 significant digits and "-" where a run has no value.
struct ComparisonGrid
{
	std::vector<std::string> labels;
	std::vector<std::string> keys;
	std::vector<std::vector<std::string>> cells;
};
ComparisonGrid comparisonGrid(const std::vector<Stats>& runs);

std::string comparisonText(const std::vector<Stats>& runs);
std::string comparisonMarkdown(const std::vector<Stats>& runs);
std::string comparisonCsv(const std::vector<Stats>& runs);

}  // namespace esif
