// Solves restricted to elimination-tree paths (EliminationTreeSolves.h)
// against dense solves, on a CHOLMOD simplicial LDL^T factor of a matrix
// with twelve independent blocks joined by a small separator: a path from one
// block never enters another, so the restricted solves must read fewer
// columns than the whole factor and still be exact.

#include "NaturalOrderFactor.h"
#include "sparse/EliminationTreeSolves.h"

#include <Eigen/Dense>
#include <algorithm>
#include <gtest/gtest.h>
#include <random>

namespace
{
using namespace esif;

constexpr int kBlocks = 12, kBlockSize = 25, kSeparator = kBlocks, kN = kBlocks * kBlockSize + kSeparator;

/// Twelve random sparse SPD blocks, each linked to a shared separator (the
/// last kSeparator scalars), diagonally dominant: cond(A) < 10, so dense and
/// sparse solves agree to ~1e-14; 1e-12 is the tolerance below.
Eigen::MatrixXd blocksWithSeparator(unsigned seed)
{
	std::mt19937 rng(seed);
	std::uniform_real_distribution<double> u(-1.0, 1.0);
	Eigen::MatrixXd A = Eigen::MatrixXd::Zero(kN, kN);
	const auto link = [&](int i, int j) {
		if (i != j) A(i, j) = A(j, i) = u(rng);
	};
	for (int b = 0; b < kBlocks; ++b)
	{
		const int o = b * kBlockSize;
		for (int i = 0; i + 1 < kBlockSize; ++i) link(o + i, o + i + 1);
		for (int k = 0; k < kBlockSize; ++k) link(o + static_cast<int>(rng() % kBlockSize), o + static_cast<int>(rng() % kBlockSize));
		link(o + kBlockSize - 1, kBlocks * kBlockSize + b);
	}
	for (int i = kBlocks * kBlockSize; i + 1 < kN; ++i) link(i, i + 1);
	for (int i = 0; i < kN; ++i) A(i, i) = A.row(i).cwiseAbs().sum() + 0.5;
	return A;
}

Eigen::VectorXd randomVector(unsigned seed)
{
	std::mt19937 rng(seed);
	std::normal_distribution<double> n;
	Eigen::VectorXd b(kN);
	for (int i = 0; i < kN; ++i) b(i) = n(rng);
	return b;
}

class EliminationTreeSolves : public ::testing::Test
{
   protected:
	void SetUp() override
	{
		A_ = blocksWithSeparator(3);
		// Natural order: the blocks, then the separator, as a nested
		// dissection would order them.
		L_ = test::naturalOrderFactor(A_, c_);
		ASSERT_TRUE(L_);
		ASSERT_EQ(c_->status, CHOLMOD_OK);
		ASSERT_FALSE(L_->is_super);
		ASSERT_FALSE(L_->is_ll);
		perm_ = static_cast<const int*>(L_->Perm);
	}
	/// y = L^-1 P b, what the incremental factor carries along.
	std::vector<double> forwardSolution(const Eigen::VectorXd& b)
	{
		auto B = zeroDense(kN, 1, c_);
		std::copy(b.data(), b.data() + kN, static_cast<double*>(B->x));
		auto PB = ownDense(cholmod_solve(CHOLMOD_P, L_.get(), B.get(), c_.get()), c_);
		auto Y = ownDense(cholmod_solve(CHOLMOD_L, L_.get(), PB.get(), c_.get()), c_);
		const auto* y = static_cast<const double*>(Y->x);
		return std::vector<double>(y, y + kN);
	}
	/// Position of scalar g in the factor's ordering.
	int positionOf(int g) const { return static_cast<int>(std::find(perm_, perm_ + kN, g) - perm_); }

	Eigen::MatrixXd A_;
	CholmodCommon c_;
	CholmodFactorPtr L_;
	const int* perm_ = nullptr;
};

TEST_F(EliminationTreeSolves, PathsAreClosedUnderTheFactorsRows)
{
	const int start = positionOf(3);  // inside block 0
	const std::vector<int> reach = pathsToRoots(*L_, {start});
	ASSERT_TRUE(std::is_sorted(reach.begin(), reach.end()));
	EXPECT_TRUE(std::binary_search(reach.begin(), reach.end(), start));
	// Every row of a reached column is reached (the rows of column j are
	// ancestors of j), and block 0 reaches no scalar of the other blocks.
	const auto* p = static_cast<const int*>(L_->p);
	const auto* nz = static_cast<const int*>(L_->nz);
	const auto* li = static_cast<const int*>(L_->i);
	for (const int j : reach)
	{
		for (int t = p[j]; t < p[j] + nz[j]; ++t) EXPECT_TRUE(std::binary_search(reach.begin(), reach.end(), li[t]));
		EXPECT_FALSE(perm_[j] >= kBlockSize && perm_[j] < kBlocks * kBlockSize) << "scalar " << perm_[j];
	}
	EXPECT_LE(reach.size(), static_cast<std::size_t>(kBlockSize + kSeparator));
}

TEST_F(EliminationTreeSolves, ForwardColumnsGiveTheCovarianceBlock)
{
	const Eigen::MatrixXd P = A_.inverse();
	const std::vector<int> scalars = {3, 30, 31, kN - 1};
	std::vector<int> positions;
	for (const int g : scalars) positions.push_back(positionOf(g));
	const Eigen::MatrixXd Z = scaledForwardColumns(*L_, positions, pathsToRoots(*L_, positions));
	const Eigen::MatrixXd block = Z * Z.transpose();
	for (std::size_t a = 0; a < scalars.size(); ++a)
		for (std::size_t b = 0; b < scalars.size(); ++b)
			EXPECT_NEAR(block(a, b), P(scalars[a], scalars[b]), 1e-12) << scalars[a] << "," << scalars[b];
}

TEST_F(EliminationTreeSolves, PartialBackSubstitutionIsExactAndReusesWhatItSolved)
{
	const Eigen::VectorXd b = randomVector(9);
	const Eigen::VectorXd x = A_.llt().solve(b);
	const std::vector<double> y_values = forwardSolution(b);
	const double* y = y_values.data();

	PartialBackSubstitution partial;
	const Eigen::VectorXd first = partial.solveAt(*L_, y, {positionOf(3), positionOf(4)});
	EXPECT_NEAR(first(0), x(3), 1e-12);
	EXPECT_NEAR(first(1), x(4), 1e-12);
	const long after_first = partial.columnsSolved();
	EXPECT_LE(after_first, kBlockSize + kSeparator);  // block 0 and the separator, not the factor

	// A second read in another block solves that block's path only; the
	// separator it shares is kept.
	const Eigen::VectorXd second = partial.solveAt(*L_, y, {positionOf(40)});
	EXPECT_NEAR(second(0), x(40), 1e-12);
	EXPECT_LE(partial.columnsSolved() - after_first, kBlockSize);
	// Read again: nothing to solve.
	const long solved = partial.columnsSolved();
	EXPECT_NEAR(partial.solveAt(*L_, y, {positionOf(3)})(0), x(3), 1e-12);
	EXPECT_EQ(partial.columnsSolved(), solved);
	// After invalidate() the values are solved again.
	partial.invalidate();
	EXPECT_NEAR(partial.solveAt(*L_, y, {positionOf(3)})(0), x(3), 1e-12);
	EXPECT_GT(partial.columnsSolved(), solved);
}

TEST_F(EliminationTreeSolves, ReadingEverythingSolvesEachColumnOnce)
{
	// Read one scalar at a time, as a whole estimate does: every value
	// exact, every column solved once.
	const Eigen::VectorXd b = randomVector(4);
	const Eigen::VectorXd x = A_.llt().solve(b);
	const std::vector<double> y = forwardSolution(b);
	PartialBackSubstitution partial;
	for (int g = 0; g < kN; ++g) EXPECT_NEAR(partial.solveAt(*L_, y.data(), {positionOf(g)})(0), x(g), 1e-12) << g;
	EXPECT_EQ(partial.columnsSolved(), kN);
}

TEST_F(EliminationTreeSolves, PositionsOutsideTheFactorAreRefused)
{
	EXPECT_THROW(pathsToRoots(*L_, {kN}), std::out_of_range);
	PartialBackSubstitution partial;
	std::vector<double> y(kN, 0.0);
	EXPECT_THROW(partial.solveAt(*L_, y.data(), {-1}), std::out_of_range);
}

TEST_F(EliminationTreeSolves, TheRootSeparatorIsTheDenseTrailingTriangle)
{
	// The separator here is a chain: only its last two columns are full.
	EXPECT_EQ(denseTrailingColumns(*L_, kN), 2);

	// Twenty leaves, each linked to two of six hub scalars that form a
	// clique: eliminating the leaves first leaves the hubs a full triangle,
	// and a leaf's column (itself and two hubs) is not part of it.
	constexpr int leaves = 20, hubs = 6, n = leaves + hubs;
	Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
	for (int i = 0; i < leaves; ++i)
	{
		A(i, leaves + i % hubs) = A(leaves + i % hubs, i) = 0.3;
		A(i, leaves + (i + 1) % hubs) = A(leaves + (i + 1) % hubs, i) = -0.2;
	}
	for (int a = leaves; a < n; ++a)
		for (int b = leaves; b < a; ++b) A(a, b) = A(b, a) = 0.1;
	for (int i = 0; i < n; ++i) A(i, i) = A.row(i).cwiseAbs().sum() + 1.0;
	CholmodCommon c;
	const auto L = test::naturalOrderFactor(A, c);
	ASSERT_TRUE(L);
	ASSERT_EQ(c->status, CHOLMOD_OK);
	ASSERT_FALSE(L->is_super);
	EXPECT_EQ(denseTrailingColumns(*L, n), hubs);
}

}  // namespace
