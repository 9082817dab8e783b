#include "ReferenceChoice.h"

#include <esif/relative/ReferencePair.h>

namespace esif::lmj
{
namespace
{
bool clear(const std::vector<Eigen::Vector2d>& points, int i, double min_clearance_m)
{
	for (int j = 0; j < static_cast<int>(points.size()); ++j)
		if (j != i && (points[j] - points[i]).norm() < min_clearance_m) return false;
	return true;
}
}  // namespace

std::optional<std::pair<int, int>> chooseReferenceFeatures(
	const std::vector<Eigen::Vector2d>& points, const std::vector<int>& eligible, double min_separation_m,
	double min_clearance_m)
{
	std::vector<int> usable;
	std::vector<relative::ReferenceCandidate> candidates;
	for (const int i : eligible)
		if (clear(points, i, min_clearance_m))
		{
			usable.push_back(i);
			candidates.push_back({points[i], static_cast<long>(usable.size())});
		}
	// No robot at the origin: the angle rule is off (0), the baseline rule on.
	const relative::ReferenceRules rules{relative::ReferencePolicy::Widest, min_separation_m, 0.0};
	const auto pair = relative::chooseReferencePair(candidates, rules);
	if (!pair) return std::nullopt;
	return std::make_pair(usable[pair->first], usable[pair->second]);
}

}  // namespace esif::lmj
