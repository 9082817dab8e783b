#include <esif/association/TentativeFeatures.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <limits>

namespace esif
{
bool TentativeFeatures::confirm(std::optional<LandmarkId> id, const Eigen::Vector2d& position,
									 const Eigen::Matrix2d& cov, std::size_t step)
{
	expire(step);
	const auto k = partner(id, position, cov);
	if (k && distance2(tentative_[*k], position, cov) <= gate_chi2_)
	{
		tentative_.erase(tentative_.begin() + static_cast<long>(*k));
		return true;
	}
	// A sighting that contradicts the tentative feature of its ID replaces it:
	// either may be the bad one, and the next sighting decides.
	if (k && id) tentative_.erase(tentative_.begin() + static_cast<long>(*k));
	tentative_.push_back({id, position, cov, step});
	return false;
}

void TentativeFeatures::expire(std::size_t step)
{
	tentative_.erase(std::remove_if(tentative_.begin(), tentative_.end(),
									[&](const Tentative& t) { return step > t.step + window_steps_; }),
					 tentative_.end());
}

std::optional<std::size_t> TentativeFeatures::partner(std::optional<LandmarkId> id,
														   const Eigen::Vector2d& position,
														   const Eigen::Matrix2d& cov) const
{
	if (id)
	{
		for (std::size_t k = 0; k < tentative_.size(); ++k)
			if (tentative_[k].id == id) return k;
		return std::nullopt;
	}
	std::optional<std::size_t> best;
	double best_d2 = std::numeric_limits<double>::infinity();
	for (std::size_t k = 0; k < tentative_.size(); ++k)
	{
		if (tentative_[k].id) continue;
		const double d2 = distance2(tentative_[k], position, cov);
		if (d2 < best_d2)
		{
			best_d2 = d2;
			best = k;
		}
	}
	return best;
}

double TentativeFeatures::distance2(const Tentative& t, const Eigen::Vector2d& position,
										 const Eigen::Matrix2d& cov) const
{
	const Eigen::Vector2d d = position - t.position;
	const Eigen::LDLT<Eigen::Matrix2d> ldlt(t.cov + cov);
	if (ldlt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
	return d.dot(ldlt.solve(d));
}

}  // namespace esif
