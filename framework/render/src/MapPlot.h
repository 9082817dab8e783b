#pragma once
/// \file MapPlot.h
/// What map.png and maps_overlay.png draw alike: metric axes at one scale
/// on both, framed on a box, and paths simplified to a tolerance.

#include "MapGeometry.h"
#include "PlotScript.h"

#include <string>
#include <vector>

namespace esif::map_plot
{
/// Equal scales on x and y in metres, the frame drawn all round, the view
/// fixed to `view` (what falls outside is clipped).
inline std::string equalScaleAxes(const map_geometry::Bounds& view)
{
	return "set border 15\nset xtics mirror\nset ytics mirror\nset size ratio -1\n"
		   "set xlabel 'x [m]'\nset ylabel 'y [m]'\n"
		   "set xrange [" + plot::number(view.x_min) + ":" + plot::number(view.x_max) + "]\n"
		   "set yrange [" + plot::number(view.y_min) + ":" + plot::number(view.y_max) + "]";
}

/// The points of `pts` that keep the polyline within `tolerance` of all of
/// them (map_geometry::simplifiedIndices), as (x, y) rows.
inline plot::DataBlock polyline(const std::vector<Eigen::Vector2d>& pts, double tolerance)
{
	plot::DataBlock block;
	for (const std::size_t i : map_geometry::simplifiedIndices(pts, tolerance)) block.row({pts[i].x(), pts[i].y()});
	return block;
}

}  // namespace esif::map_plot
