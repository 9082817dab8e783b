#pragma once
/// \file Replay.h
/// The replay loop: feeds every step to a plugin, times it, records the
/// trajectory, keyframes and association decisions.

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
};

/// Runs `plugin` over every step of `log`. A NumericalError from the plugin
/// is rethrown with the step index prefixed.
ReplayResult replay(FilterPlugin& plugin, const Rawlog& log, const ReplayOptions& options);

}  // namespace esif
