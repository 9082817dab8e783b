#include <esif/association/Chi2.h>
#include <esif/ekf/CoincidentLandmarks.h>

namespace esif
{
CoincidentLandmarks::CoincidentLandmarks(int min_matches, double chi2_quantile)
	: min_matches_(min_matches), gate_d2_(min_matches > 0 ? chi2Quantile(chi2_quantile, 2) : 0)
{
}

bool CoincidentLandmarks::eligible(LandmarkId id) const
{
	const auto it = matches_.find(id);
	return it != matches_.end() && it->second >= min_matches_ && !named_by_sensor_.count(id);
}

std::optional<std::pair<std::size_t, std::size_t>> CoincidentLandmarks::nextPair(
	const EkfSlamCore& core, const std::vector<LandmarkId>& ids) const
{
	if (!enabled()) return std::nullopt;
	std::vector<std::size_t> candidates;
	for (std::size_t i = 0; i < ids.size(); ++i)
		if (eligible(ids[i])) candidates.push_back(i);
	std::optional<std::pair<std::size_t, std::size_t>> best;
	double best_d2 = gate_d2_;
	for (std::size_t u = 0; u < candidates.size(); ++u)
		for (std::size_t v = u + 1; v < candidates.size(); ++v)
		{
			const std::size_t a = candidates[u], b = candidates[v];
			// The covariance S of the difference is at most 2 (P_aa + P_bb),
			// so d2 >= |delta|^2 / (2 tr(P_aa + P_bb)): beyond the gate
			// without forming S.
			const double spread = 2 * (core.landmarkCov(a).trace() + core.landmarkCov(b).trace());
			if ((core.landmark(a) - core.landmark(b)).squaredNorm() > best_d2 * spread) continue;
			const double d2 = core.coincidenceDistance2(a, b);
			if (d2 < best_d2) best_d2 = d2, best = std::make_pair(a, b);
		}
	return best;
}

void CoincidentLandmarks::recordMerge(LandmarkId kept, LandmarkId dropped)
{
	stands_for_[kept] = standsFor(kept) + standsFor(dropped);
	stands_for_.erase(dropped);
	merged_into_[dropped] = kept;
	matches_[kept] += matches_[dropped];
	matches_.erase(dropped);
}

int CoincidentLandmarks::standsFor(LandmarkId id) const
{
	const auto it = stands_for_.find(id);
	return it == stands_for_.end() ? 1 : it->second;
}

LandmarkId CoincidentLandmarks::finalId(LandmarkId id) const
{
	for (auto it = merged_into_.find(id); it != merged_into_.end(); it = merged_into_.find(id)) id = it->second;
	return id;
}

}  // namespace esif
