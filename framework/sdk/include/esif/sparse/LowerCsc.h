#pragma once
/// \file LowerCsc.h
/// A lower-triangular sparse matrix in compressed columns, diagonal entry
/// first in each column and row indices ascending: the form of the
/// incomplete-Cholesky factor and of its inputs. Columns can be cut off and
/// appended, which is how the trailing block of a factor is replaced
/// (book eq. 3.31).

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace esif
{
struct LowerCsc
{
	int n = 0;                    ///< columns (and rows)
	std::vector<int> col_ptr{0};  ///< size n + 1
	std::vector<int> row_idx;
	std::vector<double> values;

	std::size_t nonZeros() const { return row_idx.size(); }

	/// The lower triangle of a dense symmetric matrix, exact zeros left out
	/// (the diagonal is always stored).
	static LowerCsc fromDenseLower(const Eigen::MatrixXd& S);
	/// The dense lower-triangular matrix.
	Eigen::MatrixXd toDense() const;

	/// Keeps columns [0, columns) only. Rows of those columns may exceed
	/// `columns`; `n` becomes `rows`.
	void truncateColumns(int columns, int rows);

	/// Appends the columns of `tail` with its row indices shifted by
	/// `offset`; n grows to offset + tail.n.
	void appendColumns(const LowerCsc& tail, int offset);

	/// Solves L y = b in place (forward substitution).
	void solveLower(Eigen::Ref<Eigen::VectorXd> b) const;
	/// Solves L^T y = b in place (backward substitution).
	void solveLowerTransposed(Eigen::Ref<Eigen::VectorXd> b) const;
};

}  // namespace esif
