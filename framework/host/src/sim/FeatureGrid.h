#pragma once
/// \file FeatureGrid.h
/// The simulator's features bucketed in square cells, so that a scan looks
/// only at the features near the sensor: without it each scan tested every
/// feature of the world, a cost of features x steps that a city-sized world
/// (10^5 features, 5 x 10^5 steps) cannot pay.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace esif
{
class FeatureGrid
{
   public:
	/// Buckets `points` in square cells over their bounding box: cells of
	/// `cell_size_m` (> 0), or larger where the points spread so far that
	/// there would be more than kMaxCellsPerSide of them per side.
	FeatureGrid(const std::vector<Eigen::Vector2d>& points, double cell_size_m);

	static constexpr double kMaxCellsPerSide = 2048;

	/// Indices (into the points given at construction) of every point within
	/// `radius_m` of `centre`, and possibly some farther ones (those of the
	/// cells the disc touches), in increasing order: a caller that loops over
	/// them visits the points in the same order as a loop over all points.
	void near(const Eigen::Vector2d& centre, double radius_m, std::vector<std::size_t>& out) const;

   private:
	long cellX(double x) const;
	long cellY(double y) const;

	double cell_m_;
	Eigen::Vector2d origin_{0, 0};
	long columns_ = 0, rows_ = 0;
	std::vector<std::size_t> cell_start_;  // CSR: points of cell c are order_[cell_start_[c] .. cell_start_[c + 1])
	std::vector<std::size_t> order_;
};

}  // namespace esif
