#pragma once
/// \file NaturalOrderFactor.h
/// Test helper: CHOLMOD's simplicial LDL^T of a small dense matrix in its
/// natural order, the way the incremental factor keeps a given ordering, so
/// a test knows which scalar sits at which position of the factor.

#include "sparse/Cholmod.h"
#include <esif/sparse/LowerCsc.h>

#include <Eigen/Core>
#include <vector>

namespace esif::test
{
/// The factor of A (lower triangle read), or null if CHOLMOD's analysis
/// failed; c's status tells whether the numeric factorisation succeeded.
inline CholmodFactorPtr naturalOrderFactor(const Eigen::MatrixXd& A, CholmodCommon& c)
{
	c.useGivenOrderingForModification();
	auto S = toCholmod(LowerCsc::fromDenseLower(A), c);
	std::vector<int> natural(static_cast<std::size_t>(A.rows()));
	for (std::size_t g = 0; g < natural.size(); ++g) natural[g] = static_cast<int>(g);
	auto L = ownFactor(cholmod_analyze_p(S.get(), natural.data(), nullptr, 0, c.get()), c);
	if (L) cholmod_factorize(S.get(), L.get(), c.get());
	return L;
}
}  // namespace esif::test
