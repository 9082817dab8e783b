// Storage and updates of the information form (book eq. 3.15) against
// dense arithmetic: block-sparse storage, compressed orderings, the EIF
// update with its linearisation point, priors, input errors.

#include <esif/core/Errors.h>
#include <esif/sparse/BlockSparseMatrix.h>
#include <esif/sparse/InformationForm.h>
#include <esif/sparse/LowerCsc.h>
#include "sparse/Cholmod.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <algorithm>
#include <numeric>
#include <random>

namespace
{
using namespace esif;

/// Dense lower triangle of a LowerCsc.
Eigen::MatrixXd denseLower(const LowerCsc& A)
{
	Eigen::MatrixXd M = Eigen::MatrixXd::Zero(A.n, A.n);
	for (int j = 0; j < A.n; ++j)
		for (int t = A.col_ptr[j]; t < A.col_ptr[j + 1]; ++t) M(A.row_idx[t], j) = A.values[t];
	return M;
}

/// `variables` blocks (3x3 where dim_3(k), else 2x2) and `updates` random
/// blocks added at random places (symmetric on the diagonal).
BlockSparseMatrix randomBlockMatrix(std::mt19937& rng, int variables, int updates, bool (*dim_3)(int))
{
	std::normal_distribution<double> n(0, 1);
	BlockSparseMatrix M;
	for (int k = 0; k < variables; ++k) M.addBlockVariable(dim_3(k) ? 3 : 2);
	for (int k = 0; k < updates; ++k)
	{
		const int i = static_cast<int>(rng() % variables), j = static_cast<int>(rng() % variables);
		Eigen::MatrixXd B(M.blockDim(i), M.blockDim(j));
		for (int r = 0; r < B.rows(); ++r)
			for (int c = 0; c < B.cols(); ++c) B(r, c) = n(rng);
		if (i == j) B = (B + B.transpose()).eval();
		M.addBlock(i, j, B);
	}
	return M;
}

TEST(BlockSparseMatrix, StoresSymmetricBlocksAndCountsNonZeros)
{
	BlockSparseMatrix M;
	const int a = M.addBlockVariable(2), b = M.addBlockVariable(3), c = M.addBlockVariable(2);
	EXPECT_EQ(M.scalarDim(), 7);
	EXPECT_EQ(M.nonZeros(), 4u + 9u + 4u);  // the zero diagonal blocks exist from the start
	Eigen::MatrixXd ab(3, 2);
	ab << 1, 2, 3, 4, 5, 6;
	M.addBlock(b, a, ab);
	M.addBlock(b, a, ab);  // accumulates into the same block
	EXPECT_EQ(M.nonZeros(), 17u + 2 * 6u);
	const Eigen::MatrixXd D = M.toDense();
	EXPECT_TRUE(D.block(2, 0, 3, 2).isApprox(2 * ab));
	EXPECT_TRUE(D.block(0, 2, 2, 3).isApprox(2 * ab.transpose()));
	EXPECT_TRUE(D.block(5, 0, 2, 5).isZero());
	EXPECT_EQ(M.column(a).size(), 2u);
	EXPECT_EQ(M.column(c).size(), 1u);
	EXPECT_THROW(M.addBlock(a, b, ab), std::invalid_argument);  // 3x2 is not a (2, 3) block
}

TEST(BlockSparseMatrix, MultiplyAndPermutedLowerMatchDense)
{
	std::mt19937 rng(3);
	std::normal_distribution<double> n(0, 1);
	const BlockSparseMatrix M = randomBlockMatrix(rng, 6, 12, [](int k) { return k % 2 == 1; });
	const Eigen::MatrixXd D = M.toDense();
	const int N = M.scalarDim();
	Eigen::VectorXd x(N), y;
	for (int k = 0; k < N; ++k) x[k] = n(rng);
	M.multiply(x, y);
	EXPECT_LT((y - D * x).norm(), 1e-12 * D.norm() * x.norm());
	EXPECT_TRUE(M.diagonal().isApprox(D.diagonal()));

	// A random permutation plus 3 padding rows: P [D 0; 0 I] P^T, lower part.
	std::vector<int> position(N + 3);
	std::iota(position.begin(), position.end(), 0);
	std::shuffle(position.begin(), position.end(), rng);
	Eigen::MatrixXd bordered = Eigen::MatrixXd::Identity(N + 3, N + 3);
	bordered.topLeftCorner(N, N) = D;
	Eigen::MatrixXd expected(N + 3, N + 3);
	for (int g = 0; g < N + 3; ++g)
		for (int h = 0; h < N + 3; ++h) expected(position[g], position[h]) = bordered(g, h);
	const LowerCsc L = M.permutedLower(position, N + 3);
	EXPECT_TRUE(denseLower(L).isApprox(Eigen::MatrixXd(expected.triangularView<Eigen::Lower>())));
	for (int j = 0; j < L.n; ++j)
	{
		ASSERT_EQ(L.row_idx[L.col_ptr[j]], j) << "diagonal first";
		for (int t = L.col_ptr[j] + 1; t < L.col_ptr[j + 1]; ++t) ASSERT_LT(L.row_idx[t - 1], L.row_idx[t]);
	}
}

TEST(BlockSparseMatrix, NaturalLowerStraightIntoCholmodEqualsThePermutedLowerCopied)
{
	// The fresh factorisations' direct build: the same columns, rows and
	// values as permutedLower in the natural order copied by toCholmod, with
	// the padding, on a random pattern of 2x2 and 3x3 blocks.
	std::mt19937 rng(5);
	const BlockSparseMatrix M = randomBlockMatrix(rng, 9, 20, [](int k) { return k % 3 == 0; });
	const int size = M.scalarDim() + 4;
	std::vector<int> identity(size);
	std::iota(identity.begin(), identity.end(), 0);
	CholmodCommon common;
	const auto expected = toCholmod(M.permutedLower(identity, size), common);
	const auto direct = naturalLowerToCholmod(M, size, common);
	ASSERT_EQ(direct->nrow, expected->nrow);
	ASSERT_EQ(direct->stype, expected->stype);
	const auto* ep = static_cast<const int*>(expected->p);
	const auto* dp = static_cast<const int*>(direct->p);
	ASSERT_TRUE(std::equal(ep, ep + size + 1, dp));
	EXPECT_TRUE(std::equal(static_cast<const int*>(expected->i), static_cast<const int*>(expected->i) + ep[size],
						   static_cast<const int*>(direct->i)));
	EXPECT_TRUE(std::equal(static_cast<const double*>(expected->x), static_cast<const double*>(expected->x) + ep[size],
						   static_cast<const double*>(direct->x)));
}

TEST(LowerCsc, SolvesAndSplicesTrailingColumns)
{
	LowerCsc L;
	L.n = 3;
	L.col_ptr = {0, 3, 5, 6};
	L.row_idx = {0, 1, 2, 1, 2, 2};
	L.values = {2, 1, -1, 3, 0.5, 4};
	const Eigen::MatrixXd D = denseLower(L);
	Eigen::VectorXd b(3), y;
	b << 1, 2, 3;
	y = b;
	L.solveLower(y);
	EXPECT_TRUE((D * y).isApprox(b));
	y = b;
	L.solveLowerTransposed(y);
	EXPECT_TRUE((D.transpose() * y).isApprox(b));

	// Replace the trailing 2x2 block, keep column 0.
	LowerCsc tail;
	tail.n = 2;
	tail.col_ptr = {0, 2, 3};
	tail.row_idx = {0, 1, 1};
	tail.values = {5, 6, 7};
	L.truncateColumns(1, 1);
	L.appendColumns(tail, 1);
	Eigen::MatrixXd expected = D;
	expected.bottomRightCorner(2, 2) << 5, 0, 6, 7;
	EXPECT_TRUE(denseLower(L).isApprox(expected));
}

/// A 2-point, 1-pose information form with estimates set.
struct Small
{
	InformationForm info;
	VarId p1, pose, p2;
	Small()
	{
		p1 = info.addVariable(VarKind::Point2, Eigen::Vector2d(1.0, 2.0));
		pose = info.addVariable(VarKind::Pose2, Eigen::Vector3d(0.5, -0.5, 0.3));
		p2 = info.addVariable(VarKind::Point2, Eigen::Vector2d(-1.0, 0.0));
	}
};

TEST(InformationForm, NewVariablesHaveZeroInformation)
{
	Small s;
	EXPECT_EQ(s.info.scalarDim(), 7);
	EXPECT_TRUE(s.info.matrix().toDense().isZero());
	EXPECT_TRUE(s.info.vector().isZero());
	EXPECT_TRUE(s.info.position(s.pose).isApprox(Eigen::Vector2d(0.5, -0.5)));
	EXPECT_EQ(s.info.describeScalar(3), "variable 1 (pose, component 1)");
}

TEST(InformationForm, MeasurementUpdateIsEquation315)
{
	Small s;
	// A 3-row measurement of (p2, pose): columns stacked in that order.
	Eigen::MatrixXd J(3, 5);
	J << 1, 0, -1, 0, 0.2, 0, 1, 0, -1, 0.1, 0.5, 0.5, 0, 0, 1;
	Eigen::Matrix3d R;
	R << 0.04, 0.01, 0, 0.01, 0.05, 0.002, 0, 0.002, 0.01;
	const Eigen::Vector3d innovation(0.1, -0.2, 0.05);
	const UpdateTerm term = s.info.addMeasurement({s.p2, s.pose}, J, R, innovation);

	// Dense eq. (3.15) with the full Jacobian over all 7 scalars.
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(3, 7);
	H.middleCols(5, 2) = J.leftCols(2);
	H.middleCols(2, 3) = J.rightCols(3);
	const Eigen::MatrixXd Rinv = R.inverse();
	const Eigen::MatrixXd I = H.transpose() * Rinv * H;
	const Eigen::VectorXd i = H.transpose() * Rinv * (innovation + H * s.info.estimate());
	EXPECT_LT((s.info.matrix().toDense() - I).norm(), 1e-12 * I.norm());
	EXPECT_LT((s.info.vector() - i).norm(), 1e-12 * i.norm());
	// The factored form handed to the recovery: C C^T and delta_i.
	EXPECT_LT((term.C * term.C.transpose() - J.transpose() * Rinv * J).norm(), 1e-12 * I.norm());
	EXPECT_EQ(term.vars.size(), 2u);
	EXPECT_EQ(s.info.matrix().nonZeros(), 4u + 9u + 4u + 2 * 6u);
}

/// A measurement of a point and a pose of Small: R badly scaled on purpose,
/// like the authors' Victoria Park maps (sigmas from millimetres to metres).
struct BadlyScaledMeasurement
{
	Eigen::MatrixXd J = (Eigen::MatrixXd(3, 5) << 1, 0, -1, 0, 0.2, 0, 1, 0, -1, 0.1, 0.5, 0.5, 0, 0, 1).finished();
	Eigen::Matrix3d R = (Eigen::Matrix3d() << 4e-6, 1e-7, 0, 1e-7, 0.05, 0.002, 0, 0.002, 2.0).finished();
	Eigen::Vector3d innovation{0.1, -0.2, 0.05};
};

TEST(InformationForm, InformationMeasurementEqualsTheCovarianceForm)
{
	// Eq. (5.9) given Lambda = R^-1 (a local map's information matrix) must
	// be the update of eq. (3.15) with R, to round-off.
	Small a, b;
	const BadlyScaledMeasurement m;
	const Eigen::MatrixXd& J = m.J;
	const Eigen::Matrix3d& R = m.R;
	const Eigen::Vector3d& innovation = m.innovation;
	const Eigen::Matrix3d Lambda = R.inverse();  // 3x3, for the reference only
	a.info.addMeasurement({a.p2, a.pose}, J, R, innovation);
	const UpdateTerm term = b.info.addInformationMeasurement({b.p2, b.pose}, J, Lambda, innovation);
	const Eigen::MatrixXd Ia = a.info.matrix().toDense(), Ib = b.info.matrix().toDense();
	EXPECT_LT((Ia - Ib).norm(), 1e-9 * Ia.norm());
	EXPECT_LT((a.info.vector() - b.info.vector()).norm(), 1e-9 * a.info.vector().norm());
	EXPECT_LT((term.C * term.C.transpose() - J.transpose() * Lambda * J).norm(), 1e-9 * Ia.norm());
	EXPECT_THROW(b.info.addInformationMeasurement({b.p2, b.pose}, J, -Lambda, innovation), NumericalError);
}

TEST(InformationForm, FactoredCovarianceGivesTheSameUpdate)
{
	// A kept measurement is applied again at every relinearisation with R
	// factored once: the update must be the covariance form's, bit for bit
	// (the same factor, the same solves), and a failed factor is refused.
	Small a, b;
	const BadlyScaledMeasurement m;
	const Eigen::MatrixXd R = m.R;
	const UpdateTerm ta = a.info.addMeasurement({a.p2, a.pose}, m.J, R, m.innovation);
	const UpdateTerm tb = b.info.addMeasurement({b.p2, b.pose}, m.J, Eigen::LLT<Eigen::MatrixXd>(R), m.innovation);
	EXPECT_EQ(a.info.matrix().toDense(), b.info.matrix().toDense());
	EXPECT_EQ(a.info.vector(), b.info.vector());
	EXPECT_EQ(ta.C, tb.C);
	EXPECT_THROW(b.info.addMeasurement({b.p2, b.pose}, m.J, Eigen::LLT<Eigen::MatrixXd>(-R), m.innovation),
				 NumericalError);
	EXPECT_EQ(a.info.vector(), b.info.vector());  // nothing applied by the refused call
}

TEST(InformationForm, ATermsInformationIsSymmetricAndWithdrawnAgain)
{
	// A term over three variables (a local map's shape, eq. 5.9) adds J^T
	// R^-1 J, every block equal to its mirror bit for bit, and withdrawing a
	// second term leaves the first, to round-off.
	Small s;
	Eigen::MatrixXd J(4, 7);
	J << 1, 0, -1, 0, 0.2, 0.3, 0, 0, 1, 0, -1, 0.1, 0, 0.4, 0.5, 0.5, 0, 0, 1, -1, 0, 0.1, 0, 0.7, 0.2, 0, 0, 1;
	Eigen::Matrix4d R = Eigen::Matrix4d::Identity() * 0.04;
	R(0, 1) = R(1, 0) = 0.01;
	R(2, 3) = R(3, 2) = -0.005;
	s.info.addMeasurement({s.p1, s.pose, s.p2}, J, R, Eigen::Vector4d(0.1, -0.2, 0.05, 0.0));
	const Eigen::MatrixXd I = s.info.matrix().toDense();
	EXPECT_EQ(I, I.transpose());
	// J's columns are in the state's order (p1, pose, p2).
	EXPECT_LT((I - J.transpose() * R.inverse() * J).norm(), 1e-12 * I.norm());

	// A term of the same size: withdrawing it costs a few ulps of I.
	const UpdateTerm second = s.info.addMeasurement({s.p1, s.pose, s.p2}, J, 2 * R, Eigen::Vector4d::Zero());
	s.info.subtract(second);
	EXPECT_LT((s.info.matrix().toDense() - I).norm(), 1e-13 * I.norm());
}

TEST(InformationForm, PriorAddsInformationAndMean)
{
	Small s;
	const Eigen::Matrix2d Lambda = Eigen::Vector2d(100, 400).asDiagonal();
	s.info.addPrior(s.p1, Eigen::Vector2d(3, 4), Lambda);
	EXPECT_TRUE(s.info.matrix().toDense().topLeftCorner(2, 2).isApprox(Eigen::MatrixXd(Lambda)));
	EXPECT_TRUE(s.info.vector().head(2).isApprox(Eigen::Vector2d(300, 1600)));
}

TEST(InformationForm, RejectsBadInput)
{
	Small s;
	const Eigen::MatrixXd J = Eigen::MatrixXd::Identity(2, 2);
	EXPECT_THROW(s.info.addMeasurement({s.p1}, J, -Eigen::Matrix2d::Identity(), Eigen::Vector2d::Zero()),
				 NumericalError);
	EXPECT_THROW(s.info.addMeasurement({s.p1}, J, Eigen::Matrix2d::Identity(), Eigen::Vector2d(NAN, 0)),
				 NumericalError);
	EXPECT_THROW(s.info.addMeasurement({s.pose}, J, Eigen::Matrix2d::Identity(), Eigen::Vector2d::Zero()),
				 std::invalid_argument);
	EXPECT_THROW(s.info.addMeasurement({s.p1, s.p1}, Eigen::MatrixXd::Identity(2, 4), Eigen::Matrix2d::Identity(),
									   Eigen::Vector2d::Zero()),
				 std::invalid_argument);
	EXPECT_THROW(s.info.addMeasurement({VarId{9}}, J, Eigen::Matrix2d::Identity(), Eigen::Vector2d::Zero()),
				 std::invalid_argument);
	// Nothing was applied by the failed calls.
	EXPECT_TRUE(s.info.matrix().toDense().isZero());
}

}  // namespace
