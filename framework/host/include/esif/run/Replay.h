#pragma once
/// \file Replay.h
/// The replay loop: feeds every step to a plugin, times it, records the
/// trajectory, keyframes and association decisions.
///
/// Smoothers (FilterPlugin::smoothedTrajectory) re-estimate every pose once
/// all data is in: after finish(), their trajectory replaces the online
/// robotPose() of each step in the record, keyframe poses included, so maps,
/// trajectory.tum and the accuracy figures show the smoothed estimate.
///
/// Map-joining filters (FilterPlugin::finalReports) settle a step's data
/// association only when its local map is fused: after finish(), their final
/// reports replace the online ones and the association audit is recomputed
/// from them, so associations.txt, the da_* counts and the landmark mapping
/// used for scoring carry the final landmark IDs. The landmark counts per
/// step stay those of the online reports (they are the x axis of the step
/// times, taken when the step was processed).

#include <esif/eval/AssociationAudit.h>
#include <esif/formats/RawlogReader.h>
#include <esif/formats/RunRecord.h>
#include <esif/plugin/FilterPlugin.h>
#include <esif/plugin/LocalMapJoiner.h>

#include <functional>
#include <optional>
#include <vector>

namespace esif
{
struct ReplayOptions
{
	ReplayOptions(double keyframe_min_distance = 0, bool progress = true)
		: keyframe_min_distance_m(keyframe_min_distance), progress_bar(progress)
	{
	}

	double keyframe_min_distance_m = 0;
	bool progress_bar = true;  ///< shown only when stderr is a terminal
	/// Applied to each step before the plugin sees it (a noise calibration,
	/// a recorded run's associations); none: the steps as read.
	std::function<void(StepInput&)> prepare;
};

struct ReplayResult
{
	RunRecord record;
	std::vector<double> step_us;  ///< processStep() time of each step [us]
	/// Landmarks mapped after each step: the running count of the plugin's
	/// "new landmark" decisions (the x axis of the book's Fig. 3.20).
	std::vector<std::size_t> landmark_counts;
	double finish_us = 0;  ///< time of finish() [us]
	double wall_s = 0;	///< whole replay, steps and finish() [s]
	AssociationAudit audit;
	/// The plugin's report of each step (index k = step k), for associations.txt:
	/// its final reports when it offers them, else the online ones.
	std::vector<StepReport> reports;
	/// A map-joining plugin's LocalMapJoiner::fusionCosts() after finish()
	/// (empty for other plugins), for localmap_times.png and the join_* stats.
	std::vector<LocalMapFusionCost> fusion_costs;
	/// The OSPA cut-off of the measurement noise the plugin was given
	/// (ospaCutoff(), MapOspa.h); nullopt without measurements.
	std::optional<double> ospa_cutoff_m;
};

/// Runs `plugin` over every step of `log`, kept in memory or, when the read
/// left them in the file (Rawlog::stepsLeftInFile), read again one at a
/// time (RawlogSteps.h: InputError naming the file when it changed since).
/// A NumericalError from the plugin
/// is rethrown with the step index prefixed. When the plugin offers a
/// smoothed trajectory after finish(), it must hold exactly one pose per step
/// (else std::logic_error naming the plugin: a plugin bug, not bad input); it
/// then replaces the recorded trajectory and keyframe poses. Final reports
/// likewise must hold one report per step, each with as many associations as
/// the step's online report (else std::logic_error naming the plugin); they
/// then replace `reports` and `audit` is recomputed from them.
ReplayResult replay(FilterPlugin& plugin, const Rawlog& log, const ReplayOptions& options);

}  // namespace esif
