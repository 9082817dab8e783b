// The threshold incomplete Cholesky behind the PCG preconditioner: exact
// with drop tolerance 0, an approximation that drops small entries
// otherwise, and a reported breakdown on indefinite input.

#include "sparse/IncompleteCholesky.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <random>

namespace
{
using namespace esif;

/// A sparse SPD matrix shaped like a 2-D grid Laplacian plus a diagonal
/// shift, with random positive weights: fill-in happens, and is small far
/// from the diagonal.
Eigen::MatrixXd gridMatrix(int side, unsigned seed)
{
	std::mt19937 rng(seed);
	std::uniform_real_distribution<double> w(0.5, 2.0);
	const int n = side * side;
	Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
	auto link = [&](int a, int b) {
		const double v = w(rng);
		A(a, a) += v;
		A(b, b) += v;
		A(a, b) -= v;
		A(b, a) -= v;
	};
	for (int r = 0; r < side; ++r)
		for (int c = 0; c < side; ++c)
		{
			if (c + 1 < side) link(r * side + c, r * side + c + 1);
			if (r + 1 < side) link(r * side + c, (r + 1) * side + c);
		}
	A.diagonal().array() += 0.05;
	return A;
}

TEST(IncompleteCholesky, ZeroDropToleranceIsTheCompleteFactor)
{
	const Eigen::MatrixXd A = gridMatrix(8, 1);
	const auto ic = incompleteCholesky(LowerCsc::fromDenseLower(A), 0.0, 1e-12);
	ASSERT_TRUE(ic.ok);
	const Eigen::MatrixXd L = Eigen::LLT<Eigen::MatrixXd>(A).matrixL();
	// Both are the unique Cholesky factor; rounding differs by about
	// cond(A) * eps ~ 1e3 * 1e-16.
	EXPECT_LT((ic.L.toDense() - L).norm() / L.norm(), 1e-12);
	ASSERT_EQ(ic.pivots.size(), static_cast<std::size_t>(A.rows()));
	EXPECT_NEAR(ic.pivots.back(), L(A.rows() - 1, A.rows() - 1) * L(A.rows() - 1, A.rows() - 1), 1e-12);
}

TEST(IncompleteCholesky, DropToleranceTradesFillForAccuracy)
{
	const Eigen::MatrixXd A = gridMatrix(10, 2);
	const auto exact = incompleteCholesky(LowerCsc::fromDenseLower(A), 0.0, 1e-12);
	const auto loose = incompleteCholesky(LowerCsc::fromDenseLower(A), 1e-2, 1e-12);
	const auto tight = incompleteCholesky(LowerCsc::fromDenseLower(A), 1e-7, 1e-12);
	ASSERT_TRUE(exact.ok && loose.ok && tight.ok);
	EXPECT_LT(loose.L.nonZeros(), tight.L.nonZeros());
	EXPECT_LE(tight.L.nonZeros(), exact.L.nonZeros());
	auto error = [&](const LowerCsc& L) {
		const Eigen::MatrixXd D = L.toDense();
		return (D * D.transpose() - A).norm() / A.norm();
	};
	EXPECT_GT(error(loose.L), 1e-4);  // a real approximation...
	EXPECT_LT(error(loose.L), 0.5);   // ...but a useful one
	EXPECT_LT(error(tight.L), 1e-6);
	EXPECT_LT(error(tight.L), error(loose.L));
}

TEST(IncompleteCholesky, IndefiniteInputBreaksDownAtTheFailingColumn)
{
	Eigen::MatrixXd A = gridMatrix(4, 3);
	A(5, 5) = -1.0;
	const auto ic = incompleteCholesky(LowerCsc::fromDenseLower(A), 0.0, 1e-12);
	EXPECT_FALSE(ic.ok);
	ASSERT_EQ(ic.pivots.size(), 6u);
	EXPECT_LE(ic.pivots.back(), 0.0);
}

}  // namespace
