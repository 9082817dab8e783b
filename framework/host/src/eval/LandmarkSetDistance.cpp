/// \file LandmarkSetDistance.cpp
/// OSPA and the optimal pairing of two point sets; see LandmarkSetDistance.h.

#include <esif/eval/LandmarkSetDistance.h>
#include <esif/eval/OptimalAssignment.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <stdexcept>

namespace esif
{
namespace
{
/// Union-find over the points of both sets (x first, then y).
class PointGroups
{
   public:
	explicit PointGroups(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::size_t{0}); }
	std::size_t root(std::size_t i)
	{
		while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
		return i;
	}
	void join(std::size_t a, std::size_t b) { parent_[root(a)] = root(b); }

   private:
	std::vector<std::size_t> parent_;
};

/// The points of one group: indices into x and into y.
struct PointGroup
{
	std::vector<std::size_t> xs, ys;
};

/// The points of `y` by square cells of side c: a point of x can be closer
/// than c only to points in its own cell and the eight around it, so the
/// pairs are found in O(|x| + |y| + pairs), not by comparing every pair
/// (10^10 distances for two maps of 10^5 landmarks). Points that are not
/// finite are left out: they are closer than c to nothing.
class CellIndex
{
   public:
	CellIndex(const std::vector<Eigen::Vector2d>& y, double c) : c_(c)
	{
		for (std::size_t j = 0; j < y.size(); ++j)
			if (y[j].allFinite()) cells_[cellOf(y[j])].push_back(j);
	}
	/// Calls visit(j) for every indexed point in the 3 x 3 cells around `x`.
	template <typename Visit>
	void forNeighbours(const Eigen::Vector2d& x, Visit&& visit) const
	{
		if (!x.allFinite()) return;
		const auto [cx, cy] = cellOf(x);
		for (std::int64_t dx = -1; dx <= 1; ++dx)
			for (std::int64_t dy = -1; dy <= 1; ++dy)
				if (const auto it = cells_.find({cx + dx, cy + dy}); it != cells_.end())
					for (const std::size_t j : it->second) visit(j);
	}

   private:
	using Cell = std::pair<std::int64_t, std::int64_t>;
	/// Coordinates beyond +-2^52 cells share the outermost cell: points
	/// there are still compared by their distance, only less selectively.
	std::int64_t coordinate(double v) const
	{
		constexpr double kLimit = 4503599627370496.0;  // 2^52
		return static_cast<std::int64_t>(std::clamp(std::floor(v / c_), -kLimit, kLimit));
	}
	Cell cellOf(const Eigen::Vector2d& p) const { return {coordinate(p.x()), coordinate(p.y())}; }

	double c_;
	std::map<Cell, std::vector<std::size_t>> cells_;
};

/// Groups of points linked by pairs closer than c; groups with points on
/// both sides only (a lone point can only be left unpaired).
std::vector<PointGroup> linkedGroups(
	const std::vector<Eigen::Vector2d>& x, const std::vector<Eigen::Vector2d>& y, double c)
{
	PointGroups groups(x.size() + y.size());
	const CellIndex y_cells(y, c);
	for (std::size_t i = 0; i < x.size(); ++i)
		y_cells.forNeighbours(x[i], [&](std::size_t j) {
			if ((x[i] - y[j]).norm() < c) groups.join(i, x.size() + j);
		});
	std::map<std::size_t, PointGroup> by_root;
	for (std::size_t i = 0; i < x.size(); ++i) by_root[groups.root(i)].xs.push_back(i);
	for (std::size_t j = 0; j < y.size(); ++j) by_root[groups.root(x.size() + j)].ys.push_back(j);
	std::vector<PointGroup> out;
	for (auto& [root, group] : by_root)
		if (!group.xs.empty() && !group.ys.empty()) out.push_back(std::move(group));
	return out;
}

}  // namespace

std::vector<Eigen::Vector2d> landmarkPositions(const std::vector<LandmarkEstimate>& landmarks)
{
	std::vector<Eigen::Vector2d> out;
	out.reserve(landmarks.size());
	for (const LandmarkEstimate& lm : landmarks) out.push_back(lm.mean);
	return out;
}

SetMatch matchPointSets(const std::vector<Eigen::Vector2d>& x, const std::vector<Eigen::Vector2d>& y, double c, double p)
{
	if (!(c > 0) || !(p >= 1)) throw std::invalid_argument("matchPointSets: c must be > 0 and p >= 1");
	SetMatch out;
	const std::size_t n = std::max(x.size(), y.size());
	if (n == 0) return out;
	const double cp = std::pow(c, p);
	double total = 0;  // the cost of the pairs closer than c
	std::size_t paired = 0;
	for (const PointGroup& g : linkedGroups(x, y, c))
	{
		Eigen::MatrixXd cost(g.xs.size(), g.ys.size());
		for (std::size_t a = 0; a < g.xs.size(); ++a)
			for (std::size_t b = 0; b < g.ys.size(); ++b)
				cost(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) =
					std::pow(std::min(c, (x[g.xs[a]] - y[g.ys[b]]).norm()), p);
		const auto column_of = minimumCostAssignment(cost);
		for (std::size_t a = 0; a < column_of.size(); ++a)
		{
			if (column_of[a] == kUnassigned) continue;
			const std::size_t i = g.xs[a], j = g.ys[column_of[a]];
			if ((x[i] - y[j]).norm() >= c) continue;  // costs c^p: no better than left unpaired
			total += std::pow((x[i] - y[j]).norm(), p);
			++paired;
			out.pairs.emplace_back(i, j);
		}
	}
	// Every point of the larger set not in a pair costs c^p (paired with a
	// far point of the smaller set, or with none).
	total += cp * static_cast<double>(n - paired);
	out.ospa = std::pow(total / static_cast<double>(n), 1.0 / p);
	std::sort(out.pairs.begin(), out.pairs.end());
	return out;
}

}  // namespace esif
