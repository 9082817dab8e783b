#include "ReplayLoop.h"

#include <esif/core/Elapsed.h>
#include <esif/core/Errors.h>
#include <esif/run/ProgressBar.h>

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
