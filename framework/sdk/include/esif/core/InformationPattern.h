#pragma once
/// \file InformationPattern.h
/// Sparsity of an information-form back-end's information matrix and of its
/// Cholesky factor, for pictures like the book's Fig. 3.12-3.13. Only the
/// positions of the non-zeros matter; values are kept so a caller may also
/// inspect magnitudes.

#include <Eigen/SparseCore>

#include <string>

namespace esif
{
struct InformationPattern
{
	/// Information matrix, both triangles, in the back-end's variable order.
	Eigen::SparseMatrix<double> information;
	/// Lower-triangular Cholesky factor (or incomplete-Cholesky
	/// preconditioner) in the order it was computed, which may differ from
	/// `information`'s; empty (0 x 0) when the back-end keeps none.
	Eigen::SparseMatrix<double> factor;
	/// One line saying what the factor's order is (e.g. "distance reordering").
	std::string factor_order;
};

}  // namespace esif
