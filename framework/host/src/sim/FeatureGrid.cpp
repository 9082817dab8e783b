#include "FeatureGrid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace esif
{
FeatureGrid::FeatureGrid(const std::vector<Eigen::Vector2d>& points, double cell_size_m) : cell_m_(cell_size_m)
{
	if (!(cell_size_m > 0) || !std::isfinite(cell_size_m))
		throw std::invalid_argument("FeatureGrid: the cell size must be positive");
	if (points.empty()) return;
	Eigen::Vector2d lo = points.front(), hi = points.front();
	for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
	origin_ = lo;
	cell_m_ = std::max(cell_m_, (hi - lo).maxCoeff() / kMaxCellsPerSide);
	columns_ = static_cast<long>(std::floor((hi.x() - lo.x()) / cell_m_)) + 1;
	rows_ = static_cast<long>(std::floor((hi.y() - lo.y()) / cell_m_)) + 1;

	// Counting sort of the points by cell: each cell's points stay in
	// increasing index order.
	const auto cells = static_cast<std::size_t>(columns_ * rows_);
	std::vector<std::size_t> cell_of(points.size());
	cell_start_.assign(cells + 1, 0);
	for (std::size_t i = 0; i < points.size(); ++i)
	{
		cell_of[i] = static_cast<std::size_t>(cellY(points[i].y()) * columns_ + cellX(points[i].x()));
		++cell_start_[cell_of[i] + 1];
	}
	for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
	order_.resize(points.size());
	std::vector<std::size_t> next(cell_start_.begin(), cell_start_.end() - 1);
	for (std::size_t i = 0; i < points.size(); ++i) order_[next[cell_of[i]]++] = i;
}

long FeatureGrid::cellX(double x) const
{
	return std::clamp(static_cast<long>(std::floor((x - origin_.x()) / cell_m_)), 0L, columns_ - 1);
}

long FeatureGrid::cellY(double y) const
{
	return std::clamp(static_cast<long>(std::floor((y - origin_.y()) / cell_m_)), 0L, rows_ - 1);
}

void FeatureGrid::near(const Eigen::Vector2d& centre, double radius_m, std::vector<std::size_t>& out) const
{
	out.clear();
	if (order_.empty()) return;
	// A disc entirely outside the grid touches no cell (clamping would pick the border ones).
	if (centre.x() + radius_m < origin_.x() || centre.y() + radius_m < origin_.y() ||
		centre.x() - radius_m > origin_.x() + columns_ * cell_m_ || centre.y() - radius_m > origin_.y() + rows_ * cell_m_)
		return;
	const long x0 = cellX(centre.x() - radius_m), x1 = cellX(centre.x() + radius_m);
	const long y0 = cellY(centre.y() - radius_m), y1 = cellY(centre.y() + radius_m);
	for (long y = y0; y <= y1; ++y)
		for (long x = x0; x <= x1; ++x)
		{
			const auto c = static_cast<std::size_t>(y * columns_ + x);
			out.insert(out.end(), order_.begin() + static_cast<std::ptrdiff_t>(cell_start_[c]),
					   order_.begin() + static_cast<std::ptrdiff_t>(cell_start_[c + 1]));
		}
	std::sort(out.begin(), out.end());
}

}  // namespace esif
