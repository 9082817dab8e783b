#pragma once
/// \file PivotCheck.h
/// The one place where a factorisation of the information matrix is judged
/// numerically usable, so that every recovery method reports a singular or
/// indefinite I the same way (a NumericalError naming the variable) instead
/// of returning a NaN or meaningless estimate.

#include <esif/sparse/InformationForm.h>

#include <cholmod.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace esif
{
/// Checks the pivots d_k, k >= first_position, of a factor of P I P^T
/// (k = position, `order[k]` the scalar there; scalars beyond
/// info.scalarDim() are padding rows and skipped). A pivot must be positive and d_k / I(g, g) >= min_ratio: below
/// that, cancellation has left fewer than about -log10(min_ratio / eps)
/// digits and I is numerically singular. Throws NumericalError
/// "<what>: ... at variable v (kind, component c) ...".
void checkPivots(const std::vector<double>& pivots, int first_position, const std::vector<int>& order, double min_ratio,
				 const InformationForm& info, const std::string& what);

/// The same check at `positions` only, pivots read from the simplicial
/// LDL^T factor L: after an update or row addition, the columns it changed
/// (the elimination-tree paths of the rows it touched), so the check costs
/// what the modification did, not O(n).
void checkPivotsAt(const cholmod_factor& L, const std::vector<int>& positions, const std::vector<int>& order,
				   double min_ratio, const InformationForm& info, const std::string& what);

}  // namespace esif
