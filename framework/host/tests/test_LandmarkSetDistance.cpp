// The optimal assignment against brute force, the OSPA distance against
// values worked out by hand, the OSPA cut-off of a rawlog's measurements
// and a final map's OSPA to the ground truth.

#include <esif/eval/LandmarkSetDistance.h>
#include <esif/eval/MapOspa.h>
#include <esif/eval/OptimalAssignment.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace
{
using namespace esif;
using Points = std::vector<Eigen::Vector2d>;

/// The least total cost over every injective map of the smaller side into
/// the larger, by enumerating permutations of the larger side.
double bruteForceCost(const Eigen::MatrixXd& cost)
{
	const bool rows_fewer = cost.rows() <= cost.cols();
	const Eigen::MatrixXd m = rows_fewer ? cost : Eigen::MatrixXd(cost.transpose());
	std::vector<int> cols(static_cast<std::size_t>(m.cols()));
	std::iota(cols.begin(), cols.end(), 0);
	double best = INFINITY;
	do
	{
		double total = 0;
		for (Eigen::Index i = 0; i < m.rows(); ++i) total += m(i, cols[static_cast<std::size_t>(i)]);
		best = std::min(best, total);
	} while (std::next_permutation(cols.begin(), cols.end()));
	return best;
}

double assignedCost(const Eigen::MatrixXd& cost, const std::vector<std::size_t>& column_of)
{
	double total = 0;
	for (std::size_t i = 0; i < column_of.size(); ++i)
		if (column_of[i] != kUnassigned)
			total += cost(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(column_of[i]));
	return total;
}

TEST(OptimalAssignment, MatchesBruteForceOnRandomMatrices)
{
	std::mt19937 rng(7);
	std::uniform_int_distribution<int> size(1, 6);
	std::uniform_real_distribution<double> value(0.0, 10.0);
	for (int trial = 0; trial < 400; ++trial)
	{
		Eigen::MatrixXd cost(size(rng), size(rng));
		for (Eigen::Index i = 0; i < cost.size(); ++i) cost(i) = value(rng);
		if (trial % 4 == 0) cost = cost.array().round();  // ties
		const auto column_of = minimumCostAssignment(cost);
		ASSERT_EQ(column_of.size(), static_cast<std::size_t>(cost.rows()));
		// Distinct columns, as many pairs as the smaller side.
		std::vector<std::size_t> used;
		for (const auto c : column_of)
			if (c != kUnassigned) used.push_back(c);
		std::sort(used.begin(), used.end());
		EXPECT_EQ(std::adjacent_find(used.begin(), used.end()), used.end());
		EXPECT_EQ(used.size(), static_cast<std::size_t>(std::min(cost.rows(), cost.cols())));
		EXPECT_NEAR(assignedCost(cost, column_of), bruteForceCost(cost), 1e-9) << cost;
	}
}

TEST(OptimalAssignment, GreedyIsNotOptimal)
{
	// Greedy takes the cheapest pair (1) first and must then pay 10: 11 in
	// all; the optimum pays 2 + 3.
	Eigen::MatrixXd cost(2, 2);
	cost << 2, 1, 10, 3;
	const auto column_of = minimumCostAssignment(cost);
	EXPECT_EQ(column_of, (std::vector<std::size_t>{0, 1}));
}

TEST(Ospa, HandComputedWithCardinalityError)
{
	// Two estimates 1 m and 0.5 m from two true landmarks and one true
	// landmark far away: p = 2, c = 2 -> sqrt((1 + 0.25 + 4) / 3).
	const Points x = {{0, 0}, {10, 0}};
	const Points y = {{0, 1}, {10, 0.5}, {50, 50}};
	const SetMatch m = matchPointSets(x, y, 2.0);
	EXPECT_NEAR(m.ospa, std::sqrt(5.25 / 3.0), 1e-12);
	EXPECT_EQ(m.pairs, (std::vector<std::pair<std::size_t, std::size_t>>{{0, 0}, {1, 1}}));
	// Symmetric, and with p = 1 the mean capped distance: (1 + 0.5 + 2) / 3.
	EXPECT_NEAR(matchPointSets(y, x, 2.0).ospa, m.ospa, 1e-12);
	EXPECT_NEAR(matchPointSets(x, y, 2.0, 1.0).ospa, 3.5 / 3.0, 1e-12);
}

TEST(Ospa, DistancesAreCutOffAtC)
{
	// 3 m apart with c = 2: as bad as missing, and not a pair.
	const SetMatch m = matchPointSets({{0, 0}}, {{3, 0}}, 2.0);
	EXPECT_NEAR(m.ospa, 2.0, 1e-12);
	EXPECT_TRUE(m.pairs.empty());
	EXPECT_EQ(matchPointSets({}, {}, 2.0).ospa, 0.0);
	EXPECT_NEAR(matchPointSets({}, {{1, 1}, {2, 2}}, 2.0).ospa, 2.0, 1e-12);
}

TEST(Ospa, PairsAreTheOptimumNotTheNearest)
{
	// x1 is nearest y0 (0.1 m), but pairing them leaves x0 with y1 (2.5 m):
	// 0.01 + 6.25; the optimum x0-y0 (1.1 m), x1-y1 (1.5 m) costs 1.21 + 2.25.
	const SetMatch m = matchPointSets({{0, 0}, {1, 0}}, {{1.1, 0}, {2.5, 0}}, 3.0);
	EXPECT_NEAR(m.ospa, std::sqrt(3.46 / 2.0), 1e-12);
	EXPECT_EQ(m.pairs, (std::vector<std::pair<std::size_t, std::size_t>>{{0, 0}, {1, 1}}));
}

TEST(Ospa, EqualSetsWithinCutOffGiveTheRmsOfThePairs)
{
	// p = 2, as many estimates as true landmarks, every error below c: OSPA
	// is the RMS error, the figure landmark_rmse_m gives.
	const Points truth = {{0, 0}, {5, 0}, {0, 5}};
	const Points est = {{0.3, 0}, {5, 0.4}, {0, 5}};
	EXPECT_NEAR(matchPointSets(est, truth, 1.0).ospa, std::sqrt((0.09 + 0.16) / 3.0), 1e-12);
}

TEST(Ospa, DivergedLandmarksArePairedWithNothing)
{
	const SetMatch m = matchPointSets({{std::nan(""), 0}, {0, 0}}, {{0, 0}}, 2.0);
	EXPECT_NEAR(m.ospa, std::sqrt(4.0 / 2.0), 1e-12);
	EXPECT_EQ(m.pairs.size(), 1u);
	EXPECT_THROW(matchPointSets({}, {}, 0.0), std::invalid_argument);
	EXPECT_THROW(matchPointSets({}, {}, 1.0, 0.5), std::invalid_argument);
}

TEST(Ospa, LargeMapsSplitIntoSmallProblems)
{
	// 3000 landmarks 3 m apart, each estimate 0.1 m off, c = 0.43 m: 3000
	// groups of one pair; solved whole it would be a 3000 x 3000 assignment.
	Points truth, est;
	for (int i = 0; i < 3000; ++i)
	{
		truth.emplace_back(3.0 * (i % 60), 3.0 * (i / 60));
		est.emplace_back(3.0 * (i % 60) + 0.1, 3.0 * (i / 60));
	}
	const SetMatch m = matchPointSets(est, truth, 0.43);
	EXPECT_EQ(m.pairs.size(), 3000u);
	EXPECT_NEAR(m.ospa, 0.1, 1e-9);
}

TEST(Ospa, TheSplitProblemsGiveTheWholeAssignmentsOspa)
{
	// Random maps of 40 and 50 points in a 10 m square, c = 1.5 m, p = 2:
	// the OSPA from the groups of linked points (found cell by cell) equals
	// the definition, one assignment over the whole cost matrix of
	// min(c, d)^p, with c^p for each point of the larger map left over.
	std::mt19937 rng(7);
	std::uniform_real_distribution<double> u(-5.0, 5.0);
	for (int trial = 0; trial < 20; ++trial)
	{
		Points x(40), y(50);
		for (auto& v : x) v = {u(rng), u(rng)};
		for (auto& v : y) v = {u(rng), u(rng)};
		const double c = 1.5;
		Eigen::MatrixXd cost(40, 50);
		for (Eigen::Index i = 0; i < 40; ++i)
			for (Eigen::Index j = 0; j < 50; ++j) cost(i, j) = std::pow(std::min(c, (x[i] - y[j]).norm()), 2);
		const double whole = std::sqrt((assignedCost(cost, minimumCostAssignment(cost)) + c * c * 10) / 50.0);
		EXPECT_NEAR(matchPointSets(x, y, c).ospa, whole, 1e-12) << "trial " << trial;
	}
}

TEST(Ospa, PairsAcrossCellBordersAndFarOutAreFound)
{
	// Pairs closer than c whose points fall in neighbouring cells of side c
	// (either side of 0, of 1 and of 2), and a pair of a landmark gone
	// 1e300 m out (finite, so scored), 0.5 m apart: its cell index would
	// not fit an integer, and the outermost cell still holds both.
	const SetMatch near = matchPointSets({{-0.01, 0}, {0.99, 2.0}}, {{0.01, 0}, {1.01, 1.99}}, 1.0);
	EXPECT_EQ(near.pairs.size(), 2u);
	const SetMatch far = matchPointSets({{1e300, 0}}, {{1e300, 0.5}}, 1.0);
	ASSERT_EQ(far.pairs.size(), 1u);
	EXPECT_NEAR(far.ospa, 0.5, 1e-12);
}

/// A step whose scan holds range-bearing measurements with the given ranges
/// and noise.
StepInput scanOf(const std::vector<double>& ranges, double sigma_range_m, double sigma_bearing_rad)
{
	StepInput step;
	step.scan = Scan{};
	for (const double r : ranges)
	{
		RangeBearing m;
		m.range_m = r;
		m.cov = Eigen::Vector2d(sigma_range_m * sigma_range_m, sigma_bearing_rad * sigma_bearing_rad).asDiagonal();
		step.scan->measurements.push_back(m);
	}
	return step;
}

TEST(OspaCutoff, GateRadiusOfTheMedianMeasurement)
{
	// sqrt of the 0.9999 quantile of chi-square(2) = sqrt(-2 ln 1e-4).
	const double gate = std::sqrt(-2.0 * std::log(1e-4));
	EXPECT_FALSE(ospaCutoff({}));
	EXPECT_FALSE(ospaCutoff({StepInput{}}));
	// The book's laser: 0.1 m, 1 deg; up to 5 m the range sigma is the larger.
	const double deg = M_PI / 180.0;
	EXPECT_NEAR(*ospaCutoff({scanOf({1, 2, 3}, 0.1, deg), scanOf({4, 5}, 0.1, deg)}), gate * 0.1, 1e-6);
	// Bearing 0.05 rad: 0.5 m across at 10 m, 1 m at 20 m; ranges 2, 10, 20:
	// across-range sigmas 0.1, 0.5, 1.0 against 0.2 along -> median 0.5.
	EXPECT_NEAR(*ospaCutoff({scanOf({2, 10, 20}, 0.2, 0.05)}), gate * 0.5, 1e-6);
}

TEST(TruthOspa, AgainstTheTrueLandmarksMeasured)
{
	GroundTruth truth;
	truth.landmarks = {{1, {0, 0}}, {2, {10, 0}}, {3, {20, 0}}};
	Estimate est;
	const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
	est.landmarks = {{7, {0, 0.1}, I}, {8, {10, 0.2}, I}, {9, {30, 30}, I}};
	// Measured: 1 and 2. Pairs 0.1 and 0.2 m, the third estimate is extra: c^2.
	EXPECT_NEAR(truthOspa(truth, est, {1, 2}, 1.0), std::sqrt((0.01 + 0.04 + 1.0) / 3.0), 1e-12);
	// No measurement truth: every true landmark counts, landmark 3 is missed too.
	EXPECT_NEAR(truthOspa(truth, est, {}, 1.0), std::sqrt((0.01 + 0.04 + 1.0) / 3.0), 1e-12);
	est.landmarks.pop_back();
	EXPECT_NEAR(truthOspa(truth, est, {1, 2}, 1.0), std::sqrt((0.01 + 0.04) / 2.0), 1e-12);
	EXPECT_NEAR(truthOspa(truth, est, {}, 1.0), std::sqrt((0.01 + 0.04 + 1.0) / 3.0), 1e-12);
}

}  // namespace
