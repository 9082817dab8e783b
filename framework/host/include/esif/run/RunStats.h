#pragma once
/// \file RunStats.h
/// The stats.json keys every run shares (`esif run` on a rawlog or on local
/// maps, `esif localmaps check`): timings, cost, association, accuracy,
/// whole-state NEES, the plugin's counters, local-map joins, and the
/// suspect flag.

#include <esif/eval/AssociationAudit.h>
#include <esif/eval/Evaluator.h>
#include <esif/eval/StateNees.h>
#include <esif/formats/StatsJson.h>
#include <esif/plugin/FilterPlugin.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// Marks `stats` suspect or not (SuspectResult.h) and says why on stderr
/// in one warning line when it is.
void flagSuspectResult(Stats& stats);

/// Nearest-rank percentile: the smallest value with at least `p` of the
/// data at or below it; 0 for no data.
double nearestRankPercentile(std::vector<double> values, double p);

/// Peak resident memory of this process [MB].
double peakRssMb();

/// Sets KEY_mean, KEY_p50, KEY_p99 and KEY_max of `us` (0 for no data).
void setTimeStats(Stats& stats, const std::string& key, const std::vector<double>& us);

/// Sets state_dim, poses_in_state and info_nnz (null for covariance-form plugins).
void setCostStats(Stats& stats, const CostFigures& cost);

/// Sets da_new, da_matched, da_rejected, da_wrong (null without true IDs),
/// da_id_given and da_id_rejected (null on local maps).
void setAssociationStats(Stats& stats, const AssociationAudit& audit);

/// Sets the accuracy keys (landmark_rmse_m, ate_rmse_m, NEES means,
/// consistent fractions, landmarks_evaluated); null without ground truth.
void setAccuracyStats(Stats& stats, const std::optional<Accuracy>& accuracy);

/// The whole-state NEES of the plugin's final state against `reference`
/// (eval/StateNees.h), its landmarks paired through `filter_to_reference`;
/// nullopt when the plugin holds no information matrix or nothing can be
/// compared. A numerical failure of the test is a warning on stderr naming
/// the run, not a failed run: the test is a figure about the result.
std::optional<StateNees> finalStateNees(
	const FilterPlugin& plugin, const StateReference& reference,
	const std::optional<std::map<LandmarkId, LandmarkId>>& filter_to_reference, const std::string& what);

/// Sets state_nees, state_nees_dof, state_nees_lower95, state_nees_upper95,
/// state_nees_consistent (1/0), state_nees_poses and state_nees_reference
/// ("truth", a run folder, or null with every other key when not computed).
void setStateNeesStats(Stats& stats, const std::optional<StateNees>& nees, const std::string& reference);

/// Sets plugin_<name> for each of the plugin's own counters.
void setPluginCounters(Stats& stats, const CostFigures& cost);

/// Sets local_maps (maps fused), join_us_mean/p50/p99/max (each fusion's
/// time: `join_us` when the host timed it, else the plugin's own
/// LocalMapFusionCost::total_s) and join_association_us_mean (the plugin's
/// association time per fusion).
void setLocalMapJoinStats(
	Stats& stats, std::size_t local_maps, const std::vector<double>& join_us,
	const std::vector<LocalMapFusionCost>& costs);

}  // namespace esif
