#pragma once
/// \file PatternExport.h
/// The sparse core's matrices as Eigen sparse matrices, for pictures of their
/// sparsity (book Fig. 3.12-3.13) and for tests that check the pattern.

#include <esif/sparse/BlockSparseMatrix.h>
#include "sparse/Cholmod.h"
#include <esif/sparse/LowerCsc.h>

#include <Eigen/SparseCore>

namespace esif
{
/// The unit-lower-triangular L of a CHOLMOD factor (as LDL^T; the diagonal
/// holds D), in the factor's own (permuted) order, restricted to its first
/// `n` positions (the rest are padding rows for variables yet to come).
Eigen::SparseMatrix<double> toEigenSparse(const cholmod_factor& L, int n, CholmodCommon& common);

/// The incomplete factor (positions order), first `n` columns and rows.
Eigen::SparseMatrix<double> toEigenSparse(const LowerCsc& L, int n);

}  // namespace esif
