#pragma once
/// \file BaselineComparison.h
/// Every filter of the book is an approximation of the full-SLAM optimum
/// (Sec. 1.2.2.2): `esif compare` measures each run against the run that
/// computes that optimum, the optimization baseline, found by its stats
/// "formulation" ("full_slam"), never by plugin name.

#include <esif/formats/StatsJson.h>

#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// A run's formulation from its stats ("ekf_slam", "full_slam", ...);
/// "other" for stats.json files written before the key existed.
std::string runFormulation(const Stats& run);

/// The run's label; "?" when it has none.
std::string labelOf(const Stats& run);

/// Which run is the optimization baseline.
struct BaselineChoice
{
	std::optional<std::size_t> index;  ///< the first "full_slam" run; none when no run is one
	/// Set when several runs are "full_slam": says which one is used.
	std::optional<std::string> warning;
};

BaselineChoice findBaseline(const std::vector<Stats>& runs);

/// Whether any run has a landmark_rmse_m figure (data with ground truth).
bool hasGroundTruthFigures(const std::vector<Stats>& runs);

/// The keys setBaselineRatios() adds, in table order: base_landmark_rmse_ratio, base_ate_ratio.
const std::vector<std::string>& baselineRatioKeys();

/// Adds to every run its landmark_rmse_m and ate_rmse_m divided by the
/// baseline's (null when either is missing or the baseline's is zero): 1 for
/// the baseline itself, above 1 for a run less accurate than the optimum.
void setBaselineRatios(std::vector<Stats>& runs, std::size_t baseline);

/// The note printed under the tables: "base_*: ratio to the optimization
/// baseline '<label>' (1 = as accurate as the optimum)", with a newline.
std::string baselineNote(const std::string& label);

/// When the baseline's own plausibility check (the full-SLAM plugin's
/// stats plugin_optimum_plausible = 0, with plugin_chi2_per_dof and
/// plugin_degenerate_poses) says its optimum is not to be trusted: one line,
/// e.g. "baseline 'full' implausible: chi2/dof 7.1, 2 degenerate poses;
/// ratios and differences against it are not trustworthy". nullopt when the
/// key is absent or not 0.
std::optional<std::string> baselineImplausibility(const Stats& baseline);

}  // namespace esif
