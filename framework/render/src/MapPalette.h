#pragma once
/// \file MapPalette.h
/// Colours shared by map.png and scene.3Dscene, so both pictures of a run
/// read the same way: green for ground truth, blue for the estimated path,
/// red for estimated landmarks.

#include <mrpt/img/TColor.h>

namespace esif::map_palette
{
const mrpt::img::TColor kTruthPathColor(150, 215, 150);
const mrpt::img::TColor kTruthLandmarkColor(0, 150, 0);
const mrpt::img::TColor kPathColor(30, 80, 220);
const mrpt::img::TColor kLandmarkColor(210, 20, 20);

}  // namespace esif::map_palette
