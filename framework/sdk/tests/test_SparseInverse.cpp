// The Takahashi sparse inverse against the dense inverse, on CHOLMOD
// factors of every kind (simplicial LDL^T, LL^T, supernodal).

#include "sparse/Cholmod.h"
#include "sparse/SparseInverse.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <random>

namespace
{
using namespace esif;

/// A random sparse SPD matrix: a path plus random long links, diagonally
/// dominant, so its factor has fill.
Eigen::MatrixXd randomSparseSpd(int n, unsigned seed)
{
	std::mt19937 rng(seed);
	std::uniform_real_distribution<double> u(-1.0, 1.0);
	Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
	for (int i = 0; i + 1 < n; ++i) A(i, i + 1) = A(i + 1, i) = u(rng);
	for (int k = 0; k < n; ++k)
	{
		const int i = static_cast<int>(rng() % n), j = static_cast<int>(rng() % n);
		if (i != j) A(i, j) = A(j, i) = u(rng);
	}
	for (int i = 0; i < n; ++i) A(i, i) = A.row(i).cwiseAbs().sum() + 0.5;
	return A;
}

struct FactorKind
{
	int supernodal;
	bool final_ll;
	const char* name;
};

class SparseInverseTest : public ::testing::TestWithParam<FactorKind>
{
};

TEST_P(SparseInverseTest, MatchesTheDenseInverseOnThePattern)
{
	const int n = 120;
	const Eigen::MatrixXd A = randomSparseSpd(n, 5);
	const Eigen::MatrixXd Ainv = A.inverse();
	CholmodCommon c;
	c->supernodal = GetParam().supernodal;
	c->final_asis = false;
	c->final_super = GetParam().supernodal == CHOLMOD_SUPERNODAL;
	c->final_ll = GetParam().final_ll;
	auto S = toCholmod(LowerCsc::fromDenseLower(A), c);
	auto L = ownFactor(cholmod_analyze(S.get(), c.get()), c);
	ASSERT_TRUE(L);
	cholmod_factorize(S.get(), L.get(), c.get());
	ASSERT_EQ(c->status, CHOLMOD_OK);
	const SparseInverse Z(*L, c);

	// Every diagonal entry is in the pattern; compare all entries that are.
	// cond(A) is below 10 (diagonal dominance), so 1e-12 is ~100 eps.
	int compared = 0;
	for (int g = 0; g < n; ++g)
		for (int h = 0; h <= g; ++h)
		{
			if (g == h)
			{
				ASSERT_TRUE(Z.contains(g, h));
			}
			if (!Z.contains(g, h)) continue;
			EXPECT_NEAR(Z.at(g, h), Ainv(g, h), 1e-12 * Ainv.norm()) << g << "," << h;
			++compared;
		}
	EXPECT_EQ(compared, static_cast<int>(Z.nonZeros()));  // the whole pattern, and no more
	const std::vector<int> block = {7, 8};
	if (Z.contains(7, 8))
	{
		EXPECT_TRUE(Z.block(block).isApprox(Ainv.block(7, 7, 2, 2)));
	}
	// Outside the pattern there is no value to give.
	for (int g = 0; g < n; ++g)
		for (int h = 0; h < g; ++h)
			if (!Z.contains(g, h))
			{
				EXPECT_THROW(Z.at(g, h), std::out_of_range);
				return;
			}
}

INSTANTIATE_TEST_SUITE_P(
	FactorKinds, SparseInverseTest,
	::testing::Values(
		FactorKind{CHOLMOD_SIMPLICIAL, false, "simplicial_ldl"}, FactorKind{CHOLMOD_SIMPLICIAL, true, "simplicial_ll"},
		FactorKind{CHOLMOD_SUPERNODAL, true, "supernodal"}),
	[](const ::testing::TestParamInfo<FactorKind>& info) { return std::string(info.param.name); });

}  // namespace
