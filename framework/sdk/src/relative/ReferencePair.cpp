#include <esif/relative/ReferencePair.h>

#include <cmath>
#include <limits>

namespace esif::relative
{
namespace
{
bool wellConditioned(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const ReferenceRules& rules)
{
	if ((a - b).norm() < rules.min_separation_m) return false;
	// Angle subtended at the robot (the origin), in [0, pi].
	const double angle = std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b));
	return angle >= rules.min_angle_rad && angle <= M_PI - rules.min_angle_rad;
}

/// Orders the pair so f1 is the one mapped earlier (the book's f1).
std::pair<int, int> ordered(const std::vector<ReferenceCandidate>& c, int a, int b)
{
	return c[a].mapped_order <= c[b].mapped_order ? std::make_pair(a, b) : std::make_pair(b, a);
}
}  // namespace

std::optional<std::pair<int, int>> chooseReferencePair(const std::vector<ReferenceCandidate>& candidates,
													   const ReferenceRules& rules)
{
	const int n = static_cast<int>(candidates.size());
	std::optional<std::pair<int, int>> best;
	double best_score = -std::numeric_limits<double>::infinity();
	for (int a = 0; a < n; ++a)
		for (int b = a + 1; b < n; ++b)
		{
			if (!wellConditioned(candidates[a].point, candidates[b].point, rules)) continue;
			// Widest: the longest baseline; FirstMapped: the earliest pair,
			// scored so that an earlier second member wins.
			const double score = rules.policy == ReferencePolicy::Widest
				? (candidates[a].point - candidates[b].point).norm()
				: -static_cast<double>(std::max(candidates[a].mapped_order, candidates[b].mapped_order)) -
					1e-9 * static_cast<double>(std::min(candidates[a].mapped_order, candidates[b].mapped_order));
			if (score > best_score)
			{
				best_score = score;
				best = ordered(candidates, a, b);
			}
		}
	return best;
}

}  // namespace esif::relative
