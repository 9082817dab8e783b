/// \file test_FeatureGrid.cpp
/// The simulator's spatial index: a query returns every point within the
/// radius (a superset, in increasing index order), so a scan over it sees
/// what a scan over all features sees, in the same order.

#include "sim/FeatureGrid.h"

#include <Eigen/Core>
#include <gtest/gtest.h>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

using namespace esif;

namespace
{
std::vector<std::size_t> withinBruteForce(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& c, double r)
{
	std::vector<std::size_t> out;
	for (std::size_t i = 0; i < points.size(); ++i)
		if ((points[i] - c).norm() <= r) out.push_back(i);
	return out;
}
}  // namespace

TEST(FeatureGrid, AQueryHoldsEveryPointWithinTheRadiusInIndexOrder)
{
	std::mt19937 rng(7);
	std::uniform_real_distribution<double> coord(-50, 250);
	std::vector<Eigen::Vector2d> points;
	for (int i = 0; i < 3000; ++i) points.emplace_back(coord(rng), coord(rng));
	for (const double cell : {0.5, 6.2, 40.0, 1000.0})
	{
		const FeatureGrid grid(points, cell);
		std::vector<std::size_t> near;
		for (int q = 0; q < 200; ++q)
		{
			// Centres inside, on the border of and far outside the points' box.
			const Eigen::Vector2d c(coord(rng) * 1.4 - 60, coord(rng) * 1.4 - 60);
			const double r = q % 2 ? 6.2 : 17.0;
			grid.near(c, r, near);
			EXPECT_TRUE(std::is_sorted(near.begin(), near.end()));
			EXPECT_EQ(std::adjacent_find(near.begin(), near.end()), near.end()) << "an index twice";
			std::vector<std::size_t> kept;
			for (const std::size_t i : near)
				if ((points[i] - c).norm() <= r) kept.push_back(i);
			EXPECT_EQ(kept, withinBruteForce(points, c, r)) << "cell " << cell << ", query " << q;
			// Only the cells of the disc's bounding square: nothing beyond its corners, one cell out.
			for (const std::size_t i : near) EXPECT_LE((points[i] - c).norm(), std::sqrt(2.0) * (r + cell));
		}
	}
}

TEST(FeatureGrid, EmptyAndDegenerateSets)
{
	std::vector<std::size_t> near{1, 2};
	FeatureGrid({}, 5).near({0, 0}, 10, near);
	EXPECT_TRUE(near.empty());

	// All points at one spot: one cell.
	const std::vector<Eigen::Vector2d> same(5, Eigen::Vector2d(3, 3));
	FeatureGrid(same, 5).near({3, 3}, 0.1, near);
	EXPECT_EQ(near, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
	FeatureGrid(same, 5).near({300, 300}, 10, near);
	EXPECT_TRUE(near.empty());

	EXPECT_THROW(FeatureGrid(same, 0), std::invalid_argument);
	EXPECT_THROW(FeatureGrid(same, -1), std::invalid_argument);
}
