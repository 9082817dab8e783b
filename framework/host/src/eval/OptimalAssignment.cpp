/// \file OptimalAssignment.cpp
/// Kuhn-Munkres with potentials; see OptimalAssignment.h.

#include <esif/eval/OptimalAssignment.h>

#include <limits>
#include <stdexcept>

namespace esif
{
namespace
{
/// Rows <= cols. Dual potentials u (rows) and v (cols) keep every reduced
/// cost cost(i, j) - u(i) - v(j) >= 0; each row is added by a Dijkstra-like
/// search for the cheapest augmenting path over tight edges (index 0 is a
/// virtual column holding the row being added).
std::vector<std::size_t> assignRowsToColumns(const Eigen::MatrixXd& cost)
{
	const std::size_t rows = static_cast<std::size_t>(cost.rows());
	const std::size_t cols = static_cast<std::size_t>(cost.cols());
	const double inf = std::numeric_limits<double>::infinity();
	std::vector<double> u(rows + 1, 0.0), v(cols + 1, 0.0);
	std::vector<std::size_t> row_of(cols + 1, 0), way(cols + 1, 0);	 // row_of: 1-based, 0 = free
	for (std::size_t i = 1; i <= rows; ++i)
	{
		row_of[0] = i;
		std::size_t col = 0;
		std::vector<double> slack(cols + 1, inf);
		std::vector<char> used(cols + 1, 0);
		do
		{
			used[col] = 1;
			const std::size_t row = row_of[col];
			double delta = inf;
			std::size_t next = 0;
			for (std::size_t j = 1; j <= cols; ++j)
			{
				if (used[j]) continue;
				const double reduced = cost(static_cast<Eigen::Index>(row - 1), static_cast<Eigen::Index>(j - 1)) -
									   u[row] - v[j];
				if (reduced < slack[j]) slack[j] = reduced, way[j] = col;
				if (slack[j] < delta) delta = slack[j], next = j;
			}
			for (std::size_t j = 0; j <= cols; ++j)
				if (used[j])
					u[row_of[j]] += delta, v[j] -= delta;
				else
					slack[j] -= delta;
			col = next;
		} while (row_of[col] != 0);
		// Flip the augmenting path back to the virtual column.
		do
		{
			const std::size_t previous = way[col];
			row_of[col] = row_of[previous];
			col = previous;
		} while (col != 0);
	}
	std::vector<std::size_t> column_of(rows, kUnassigned);
	for (std::size_t j = 1; j <= cols; ++j)
		if (row_of[j] != 0) column_of[row_of[j] - 1] = j - 1;
	return column_of;
}
}  // namespace

std::vector<std::size_t> minimumCostAssignment(const Eigen::MatrixXd& cost)
{
	if (!cost.allFinite()) throw std::invalid_argument("minimumCostAssignment: costs must be finite");
	if (cost.rows() <= cost.cols()) return assignRowsToColumns(cost);
	const std::vector<std::size_t> row_of_column = assignRowsToColumns(cost.transpose());
	std::vector<std::size_t> column_of(static_cast<std::size_t>(cost.rows()), kUnassigned);
	for (std::size_t j = 0; j < row_of_column.size(); ++j) column_of[row_of_column[j]] = j;
	return column_of;
}

}  // namespace esif
