#pragma once
/// \file MapPalette.h
/// Colours shared by map.png and scene.3Dscene, so both pictures of a run
/// read the same way: green for ground truth, blue for the estimated path,
/// red for estimated landmarks.

#include <mrpt/img/TColor.h>

#include <cstdio>
#include <string>

namespace esif::map_palette
{
const mrpt::img::TColor kTruthPathColor(150, 215, 150);
const mrpt::img::TColor kTruthLandmarkColor(0, 150, 0);
const mrpt::img::TColor kPathColor(30, 80, 220);
const mrpt::img::TColor kLandmarkColor(210, 20, 20);

/// A colour as gnuplot reads it: "#rrggbb".
inline std::string hex(const mrpt::img::TColor& c)
{
	char buf[8];
	std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c.R, c.G, c.B);
	return buf;
}

}  // namespace esif::map_palette
