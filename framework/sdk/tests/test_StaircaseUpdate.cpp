// The staircase form of an update (StaircaseUpdate.h): the same C C^T, a
// lower staircase over the touched positions, and a cholmod_updown that
// walks less of the factor. The factor is that of twelve blocks of 25
// scalars joined by a 12-scalar separator, in natural order (the blocks,
// then the separator: the tree a nested dissection gives), so a path from a
// block's first scalar runs through the block and the separator, and a path
// from a separator scalar only through the rest of the separator.

#include "NaturalOrderFactor.h"
#include "sparse/StaircaseUpdate.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <random>

namespace
{
using namespace esif;

constexpr int kBlocks = 12, kBlockSize = 25, kSeparator = kBlocks, kN = kBlocks * kBlockSize + kSeparator;

Eigen::MatrixXd randomMatrix(Eigen::Index rows, Eigen::Index cols, unsigned seed)
{
	std::mt19937 rng(seed);
	std::normal_distribution<double> n;
	Eigen::MatrixXd M(rows, cols);
	for (Eigen::Index j = 0; j < cols; ++j)
		for (Eigen::Index i = 0; i < rows; ++i) M(i, j) = n(rng);
	return M;
}

void expectStaircaseOf(const Eigen::MatrixXd& C)
{
	const Eigen::MatrixXd S = staircase(C);
	ASSERT_EQ(S.rows(), C.rows());
	EXPECT_EQ(S.cols(), std::min(C.rows(), C.cols()));
	// Orthogonal recombination: C C^T kept to rounding. Householder QR errs
	// by a modest multiple of eps |C|^2 (eps = 2.2e-16, dimensions below
	// 20): 1e-12 relative leaves a margin of over 100.
	const Eigen::MatrixXd CCt = C * C.transpose();
	EXPECT_LT((S * S.transpose() - CCt).norm(), 1e-12 * CCt.norm());
	for (Eigen::Index j = 0; j < S.cols(); ++j)
		for (Eigen::Index i = 0; i < j; ++i) EXPECT_EQ(S(i, j), 0.0) << "row " << i << " column " << j;
}

TEST(StaircaseUpdate, KeepsCCtWithAtMostOneColumnPerRow)
{
	expectStaircaseOf(randomMatrix(12, 20, 1));  // more columns than rows: the excess goes
	expectStaircaseOf(randomMatrix(20, 6, 2));   // fewer: as many columns, one step each
	expectStaircaseOf(randomMatrix(9, 9, 3));
	Eigen::MatrixXd deficient = randomMatrix(8, 10, 7);
	deficient.col(3) = deficient.col(1);  // a repeated column and a zero row
	deficient.row(5).setZero();           // (a scalar this update leaves alone): rank 7
	expectStaircaseOf(deficient);
	const Eigen::MatrixXd one_column = randomMatrix(5, 1, 4);
	EXPECT_EQ(staircase(one_column), one_column);
}

/// Blocks, each a path of scalars linked to its own separator scalar; the
/// separator a path too; diagonally dominant (cond < 10).
Eigen::MatrixXd blocksWithSeparator()
{
	Eigen::MatrixXd A = Eigen::MatrixXd::Zero(kN, kN);
	const auto link = [&](int i, int j) { A(i, j) = A(j, i) = -0.3; };
	for (int b = 0; b < kBlocks; ++b)
	{
		const int o = b * kBlockSize;
		for (int i = 0; i + 1 < kBlockSize; ++i) link(o + i, o + i + 1);
		link(o + kBlockSize - 1, kBlocks * kBlockSize + b);
	}
	for (int i = kBlocks * kBlockSize; i + 1 < kN; ++i) link(i, i + 1);
	for (int i = 0; i < kN; ++i) A(i, i) = A.row(i).cwiseAbs().sum() + 1.0;
	return A;
}

struct Updated
{
	Eigen::VectorXd x;  ///< (A + C C^T)^-1 b from the updated factor
	double flops = 0;   ///< cholmod_updown's count (Common->modfl)
};

/// Factors A in natural order, updates it by C (rows = `rows`, ascending)
/// and solves (A + C C^T) x = b.
Updated updateAndSolve(const Eigen::MatrixXd& A, const std::vector<int>& rows, const Eigen::MatrixXd& C,
					   const Eigen::VectorXd& b)
{
	CholmodCommon c;
	auto L = test::naturalOrderFactor(A, c);
	EXPECT_TRUE(L && c->status == CHOLMOD_OK);
	auto U = ownSparse(cholmod_allocate_sparse(kN, C.cols(), C.size(), true, true, 0, CHOLMOD_REAL, c.get()), c);
	auto* p = static_cast<int*>(U->p);
	auto* i = static_cast<int*>(U->i);
	auto* x = static_cast<double*>(U->x);
	int k = 0;
	for (Eigen::Index j = 0; j < C.cols(); ++j)
	{
		p[j] = k;
		for (Eigen::Index r = 0; r < C.rows(); ++r)
			if (C(r, j) != 0.0) i[k] = rows[static_cast<std::size_t>(r)], x[k++] = C(r, j);
	}
	p[C.cols()] = k;
	EXPECT_TRUE(cholmod_updown(true, U.get(), L.get(), c.get()));
	Updated out;
	out.flops = c->modfl;
	auto B = zeroDense(kN, 1, c);
	std::copy(b.data(), b.data() + kN, static_cast<double*>(B->x));
	auto X = ownDense(cholmod_solve(CHOLMOD_A, L.get(), B.get(), c.get()), c);
	out.x = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(X->x), kN);
	return out;
}

TEST(StaircaseUpdate, SameSolutionFromFewerFlopsOfUpdown)
{
	const Eigen::MatrixXd A = blocksWithSeparator();
	// A dense 16 x 16 update of the first scalar of four blocks and the whole
	// separator, as a whitened measurement information gives: every column
	// holds the deepest row.
	std::vector<int> rows;
	for (int b = 0; b < 4; ++b) rows.push_back(b * kBlockSize);
	for (int s = 0; s < kSeparator; ++s) rows.push_back(kBlocks * kBlockSize + s);
	const Eigen::MatrixXd C = 0.5 * randomMatrix(static_cast<Eigen::Index>(rows.size()), 16, 5);
	const Eigen::VectorXd b = randomMatrix(kN, 1, 6);

	const Updated dense = updateAndSolve(A, rows, C, b);
	const Updated stair = updateAndSolve(A, rows, staircase(C), b);
	Eigen::MatrixXd updated = A;
	for (std::size_t r = 0; r < rows.size(); ++r)
		for (std::size_t s = 0; s < rows.size(); ++s)
			updated(rows[r], rows[s]) += C.row(static_cast<Eigen::Index>(r)).dot(C.row(static_cast<Eigen::Index>(s)));
	const Eigen::VectorXd reference = updated.llt().solve(b);
	// cond(A + C C^T) stays below ~1e3: both solves agree with the dense one
	// to well within 1e-10.
	EXPECT_LT((dense.x - reference).norm(), 1e-10 * reference.norm());
	EXPECT_LT((stair.x - reference).norm(), 1e-10 * reference.norm());
	// Every dense column walks four blocks' paths; in staircase form only
	// the first four do, the other twelve only what is left of the separator
	// (measured: 19,920 flops against 114,688).
	EXPECT_LT(stair.flops, 0.5 * dense.flops) << "staircase " << stair.flops << ", dense " << dense.flops;
}

}  // namespace
