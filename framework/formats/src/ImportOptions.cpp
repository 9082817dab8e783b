/// \file ImportOptions.cpp
/// See ImportOptions.h.

#include "ImportOptions.h"

#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>

#include <cmath>

namespace esif
{
void checkImportOption(
	const std::string& who, const char* flag, double value, double lo, double hi, const std::string& why)
{
	const bool inside = lo > 0 ? value >= lo : value > 0;
	if (!(std::isnormal(value) && inside && value <= hi))
		throw ConfigError(
			who + ": " + flag + " = " + formatNumber(value) + ": must be in " +
			(lo > 0 ? "[" + formatNumber(lo) : std::string("(0")) + ", " + formatNumber(hi) + "] (" + why + ")");
}

void checkSensorNoise(const std::string& who, double std_range_m, double std_bearing_deg)
{
	checkImportOption(
		who, "--std-range-m", std_range_m, kMinStdRange_m, 100.0,
		"below a micrometre no sensor measures; beyond 100 m a measurement carries no information");
	checkImportOption(
		who, "--std-bearing-deg", std_bearing_deg, kMinStdBearing_deg, 180.0,
		"below a microdegree no sensor measures; beyond 180 deg a bearing carries no information");
}

}  // namespace esif
