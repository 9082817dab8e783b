#pragma once
/// \file Replay.h
/// The replay loop: feeds every step to a plugin, times it, records the
/// trajectory, keyframes and association decisions.
///
/// Smoothers (FilterPlugin::smoothedTrajectory) re-estimate every pose once
/// all data is in: after finish(), their trajectory replaces the online
/// robotPose() of each step in the record, keyframe poses included, so maps,
/// trajectory.tum and the accuracy figures show the smoothed estimate.

#include <esif/eval/AssociationAudit.h>
#include <esif/io/RawlogReader.h>
#include <esif/io/RunRecord.h>
#include <esif/plugin/FilterPlugin.h>

#include <vector>

namespace esif
{
struct ReplayOptions
{
	double keyframe_min_distance_m = 0;
	bool progress_bar = true;  ///< shown only when stderr is a terminal
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
	/// The plugin's report of each step (index k = step k), for associations.txt.
	std::vector<StepReport> reports;
};

/// Runs `plugin` over every step of `log`. A NumericalError from the plugin
/// is rethrown with the step index prefixed. When the plugin offers a
/// smoothed trajectory after finish(), it must hold exactly one pose per step
/// (else std::logic_error naming the plugin: a plugin bug, not bad input); it
/// then replaces the recorded trajectory and keyframe poses.
ReplayResult replay(FilterPlugin& plugin, const Rawlog& log, const ReplayOptions& options);

}  // namespace esif
