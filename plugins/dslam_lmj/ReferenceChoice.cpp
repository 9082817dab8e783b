#include "ReferenceChoice.h"

#include <algorithm>
#include <limits>

namespace esif::lmj
{
namespace
{
/// Distance from point i to the nearest other point (infinity when alone).
double clearanceOf(const std::vector<Eigen::Vector2d>& points, int i)
{
	double nearest = std::numeric_limits<double>::infinity();
	for (int j = 0; j < static_cast<int>(points.size()); ++j)
		if (j != i) nearest = std::min(nearest, (points[j] - points[i]).norm());
	return nearest;
}
}  // namespace

std::optional<std::pair<int, int>> chooseReferenceFeatures(
	const std::vector<Eigen::Vector2d>& points, const std::vector<int>& eligible, double min_separation_m,
	double min_clearance_m)
{
	std::vector<double> clearance(points.size());
	for (const int i : eligible) clearance[i] = clearanceOf(points, i);
	// The widest separated pair whose f1 is clear (the earlier of the two
	// when both are); failing that, the pair whose f1 is the clearest.
	std::optional<std::pair<int, int>> widest, clearest;
	double widest_d = -1, clearest_c = -1, clearest_d = -1;
	for (std::size_t ia = 0; ia < eligible.size(); ++ia)
		for (std::size_t ib = ia + 1; ib < eligible.size(); ++ib)
		{
			const int a = eligible[ia], b = eligible[ib];
			const double d = (points[a] - points[b]).norm();
			if (d < min_separation_m) continue;
			const int f1 = clearance[a] >= clearance[b] || clearance[a] >= min_clearance_m ? a : b;
			const int f2 = f1 == a ? b : a;
			if (clearance[f1] >= min_clearance_m && d > widest_d)
			{
				widest_d = d;
				widest = std::make_pair(f1, f2);
			}
			if (clearance[f1] > clearest_c || (clearance[f1] == clearest_c && d > clearest_d))
			{
				clearest_c = clearance[f1];
				clearest_d = d;
				clearest = std::make_pair(f1, f2);
			}
		}
	return widest ? widest : clearest;
}

}  // namespace esif::lmj
