#pragma once
/// \file InputBounds.h
/// The plausibility bounds every reader applies to the values it takes from
/// a file, so a rawlog, a ground truth, a local map, a reference result and
/// a solver's g2o output are held to the same rules.

#include <cstdint>

namespace esif
{
/// Largest |coordinate| [m]: positions beyond an Earth-sized map are a
/// corrupt file or the wrong units, and the errors scored against them
/// would mean nothing.
inline constexpr double kMaxCoordinate_m = 1e7;

/// Largest |heading| [rad] of a file that may hold unwrapped headings (the
/// book authors' pose.txt does): a million radians is 160,000 turns, and a
/// double still resolves it to 1e-10 rad; beyond, wrapping loses the angle.
inline constexpr double kMaxHeading_rad = 1e6;

/// Largest landmark ID: the rawlogs carry MRPT's int32 landmark IDs, so a
/// larger one can never match a measurement.
inline constexpr std::int64_t kMaxLandmarkId = 2147483647;

}  // namespace esif
