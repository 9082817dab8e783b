#include "ReplayLoop.h"

#include <esif/core/Elapsed.h>
#include <esif/core/Errors.h>
#include <esif/run/ProgressBar.h>
#include <esif/safeio/TerminationCleanup.h>

#include <atomic>
#include <cstdio>
#include <new>

namespace esif
{
namespace
{
/// "step 12", "local map 3": input i as messages name it. Built only for a
/// message, not on every input.
std::string inputLabel(const ReplaySource& source, std::size_t i)
{
	return source.input_name + " " + std::to_string(source.input_number(i));
}

/// While the replay runs, a signal that stops it reports how far it got
/// (a run stopped by a time limit is otherwise silent about it).
class StopNoteDuringReplay
{
   public:
	StopNoteDuringReplay(const ReplaySource& source, SteadyClock::time_point start)
	{
		termination::setStopNote([this, plugin = source.plugin, input = source.input_name, count = source.count,
								  start](int sig) {
			char seconds[32];
			std::snprintf(seconds, sizeof seconds, "%.1f", microsecondsSince(start) * 1e-6);
			return "esif: " + plugin + " stopped by signal " + std::to_string(sig) + " after " +
				std::to_string(done_.load(std::memory_order_relaxed)) + " of " + std::to_string(count) + " " +
				input + "s, " + seconds + " s into the replay";
		});
	}
	~StopNoteDuringReplay() { termination::clearStopNote(); }
	StopNoteDuringReplay(const StopNoteDuringReplay&) = delete;
	StopNoteDuringReplay& operator=(const StopNoteDuringReplay&) = delete;

	void done(std::size_t n) { done_.store(n, std::memory_order_relaxed); }

   private:
	std::atomic<std::size_t> done_{0};
};

NumericalError outOfMemory(const ReplaySource& source, const std::string& when)
{
	return NumericalError(
		source.origin + ": out of memory " + when + " in plugin " + source.plugin + " (state of " + source.state() +
		")");
}
}  // namespace

ReplayTimes runReplayLoop(FilterPlugin& plugin, const ReplaySource& source, bool progress_bar)
{
	ReplayTimes out;
	out.feed_us.reserve(source.count);
	ProgressBar progress(source.plugin, progress_bar ? source.count : 0);
	const auto t_start = SteadyClock::now();
	StopNoteDuringReplay stop_note(source, t_start);
	for (std::size_t i = 0; i < source.count; ++i)
	{
		const auto t0 = SteadyClock::now();
		try
		{
			source.feed(i);
		}
		catch (const NumericalError& e)
		{
			throw NumericalError(source.origin + ": " + inputLabel(source, i) + ": " + e.what());
		}
		catch (const std::bad_alloc&)
		{
			throw outOfMemory(source, "at " + inputLabel(source, i));
		}
		out.feed_us.push_back(microsecondsSince(t0));
		source.after(i);
		progress.update(i + 1);
		stop_note.done(i + 1);
	}
	const auto t_finish = SteadyClock::now();
	try
	{
		plugin.finish();
	}
	catch (const std::bad_alloc&)
	{
		throw outOfMemory(source, "after the last " + source.input_name);
	}
	out.finish_us = microsecondsSince(t_finish);
	out.wall_s = microsecondsSince(t_start) * 1e-6;
	progress.finish();
	return out;
}

}  // namespace esif
