#pragma once
/// \file MapOverlay.h
/// maps_overlay.png: several runs' maps drawn over one reference run (for
/// real data without ground truth, the full-SLAM optimum), so a rotated,
/// stretched or diverged map shows at a glance beside the compare table.

#include <esif/formats/RunOutputReader.h>

#include <string>
#include <vector>

namespace esif
{
/// One run's path and landmarks with the label its legend entry shows.
struct MapOverlayLayer
{
	std::string label;
	RunOutputs outputs;
};

/// Writes a PNG, width_px wide and 3/4 of that high: metric grid, equal
/// scales, the reference (`layers[0]`) in black (path as a line, landmarks as
/// circles), every other layer in its own colour (path and '+' landmarks),
/// and a legend. The picture is framed on the reference (padded by a fifth),
/// so one diverged run cannot shrink everything else to a dot; what falls
/// outside is clipped. Non-finite points are left out. Throws ConfigError
/// for width_px outside [200, 16384] or no layer (before writing), and
/// InputError naming `path` when it cannot be written.
void writeMapOverlayImage(
	const std::vector<MapOverlayLayer>& layers, const std::string& title, const std::string& path, int width_px);

}  // namespace esif
