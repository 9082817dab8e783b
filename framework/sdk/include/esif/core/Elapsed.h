#pragma once
/// \file Elapsed.h
/// Time elapsed since an instant of the steady clock, for the timings the
/// host reports (per step, per fusion) and the cost figures plugins report.

#include <chrono>

namespace esif
{
using SteadyClock = std::chrono::steady_clock;

/// Seconds since `t0`.
inline double secondsSince(SteadyClock::time_point t0)
{
	return std::chrono::duration<double>(SteadyClock::now() - t0).count();
}

/// Microseconds since `t0`.
inline double microsecondsSince(SteadyClock::time_point t0)
{
	return std::chrono::duration<double, std::micro>(SteadyClock::now() - t0).count();
}

}  // namespace esif
