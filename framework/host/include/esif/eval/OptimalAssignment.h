#pragma once
/// \file OptimalAssignment.h
/// The linear assignment problem: each row of a cost matrix to its own
/// column so that the summed cost is least (Kuhn-Munkres, the Hungarian
/// method with potentials and shortest augmenting paths, O(r^2 c) for r <= c).
///
/// Written here because none of the kept libraries has a usable one: MRPT
/// 2.5 and Eigen have no assignment solver, and Boost 1.74's
/// maximum_weighted_matching (Debian 12) returns non-optimal matchings on
/// bipartite graphs and can fail to terminate (boostorg/graph issues 306,
/// 223 and 399, fixed only in later Boost releases).

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace esif
{
/// For a cost matrix with rows <= cols: the column of each row, distinct,
/// with the least total cost. With more rows than columns, the row assigned
/// to each column is found instead and returned the same way (rows left
/// without a column get kUnassigned). Costs must be finite.
std::vector<std::size_t> minimumCostAssignment(const Eigen::MatrixXd& cost);

/// The value of minimumCostAssignment for a row left without a column.
inline constexpr std::size_t kUnassigned = static_cast<std::size_t>(-1);

}  // namespace esif
