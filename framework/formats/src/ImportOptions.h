#pragma once
/// \file ImportOptions.h
/// The checks of the dataset importers' numeric options (import
/// victoria-park, import mrclam), one rule for both: every value a normal
/// finite number within its plausibility bound, and the sensor noise no
/// smaller than a rawlog can carry.

#include <string>

namespace esif
{
/// Smallest sensor noise an importer writes into a rawlog, 1 sigma: a
/// micrometre of range, a microdegree of bearing. The rawlog stores it as a
/// float and a filter squares and inverts it, so a subnormal value (1e-320
/// passes "> 0") would reach it as a zero variance.
inline constexpr double kMinStdRange_m = 1e-6;
inline constexpr double kMinStdBearing_deg = 1e-6;

/// Throws ConfigError "`who`: FLAG = V: must be in (0, hi] (why)" unless
/// `value` is a normal number in (0, hi], or in [lo, hi] when lo > 0.
void checkImportOption(
	const std::string& who, const char* flag, double value, double lo, double hi, const std::string& why);

/// --std-range-m and --std-bearing-deg: at least kMinStdRange_m and
/// kMinStdBearing_deg, at most 100 m and 180 deg (beyond, a measurement
/// carries no information).
void checkSensorNoise(const std::string& who, double std_range_m, double std_bearing_deg);

}  // namespace esif
