#pragma once
/// \file ReplayLoop.h
/// The loop both replays share (rawlog steps, Replay.cpp; local-map
/// folders, LocalMapReplay.cpp): feeds the inputs one by one, timing each,
/// then finish(), with the same error context and progress bar.

#include <esif/plugin/FilterPlugin.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace esif
{
/// What the loop feeds and how its messages name things.
struct ReplaySource
{
	std::string origin;	 ///< the rawlog or folder, first in every message
	std::string plugin;	 ///< the plugin's class name
	std::size_t count = 0;	///< inputs to feed
	std::string input_name;	 ///< "step" or "local map", as messages name input i
	/// The number messages give input i (the step index, the map's k).
	std::function<std::size_t(std::size_t)> input_number;
	/// Feeds input i to the plugin (the timed part).
	std::function<void(std::size_t)> feed;
	/// Bookkeeping after input i, outside the timed part.
	std::function<void(std::size_t)> after;
	/// The plugin's state for an out-of-memory message ("12 landmarks").
	std::function<std::string()> state;
};

struct ReplayTimes
{
	std::vector<double> feed_us;  ///< of each input [us]
	double finish_us = 0;  ///< of finish() [us]
	double wall_s = 0;	///< every input and finish() [s]
};

/// Runs the loop. A NumericalError is rethrown as "<origin>: <input> <n>:
/// <what>"; running out of memory is a NumericalError too (exit code 3: the
/// input is valid, but this estimator cannot carry on with it; a bad-input
/// code would send the user looking for a fault in the data or config).
ReplayTimes runReplayLoop(FilterPlugin& plugin, const ReplaySource& source, bool progress_bar);

}  // namespace esif
