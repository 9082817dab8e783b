#include "sparse/PatternExport.h"

#include <vector>

namespace esif
{
namespace
{
using Triplets = std::vector<Eigen::Triplet<double>>;

Eigen::SparseMatrix<double> fromTriplets(int n, const Triplets& t)
{
	Eigen::SparseMatrix<double> M(n, n);
	M.setFromTriplets(t.begin(), t.end());
	return M;
}
}  // namespace

Eigen::SparseMatrix<double> toEigenSparse(const BlockSparseMatrix& M)
{
	Triplets t;
	t.reserve(M.nonZeros());
	for (int j = 0; j < M.blockCount(); ++j)
		for (const auto& e : M.column(j))
			for (int c = 0; c < M.blockDim(j); ++c)
				for (int r = 0; r < M.blockDim(e.row); ++r)
					t.emplace_back(M.blockOffset(e.row) + r, M.blockOffset(j) + c, e.value(r, c));
	return fromTriplets(M.scalarDim(), t);
}

Eigen::SparseMatrix<double> toEigenSparse(const cholmod_factor& L, int n, CholmodCommon& common)
{
	// A simplicial LDL^T copy has one column per scalar with d_j first; a
	// supernodal or LL^T factor is converted on the copy.
	auto copy = ownFactor(cholmod_copy_factor(const_cast<cholmod_factor*>(&L), common.get()), common);
	if (!copy) common.check("exporting the factor: copy");
	if (copy->is_super || copy->is_ll)
	{
		cholmod_change_factor(CHOLMOD_REAL, false, false, true, true, copy.get(), common.get());
		common.check("exporting the factor: conversion to simplicial LDL^T");
	}
	const auto* p = static_cast<const int*>(copy->p);
	const auto* nz = static_cast<const int*>(copy->nz);
	const auto* li = static_cast<const int*>(copy->i);
	const auto* lx = static_cast<const double*>(copy->x);
	Triplets t;
	for (int j = 0; j < n; ++j)
		for (int k = p[j]; k < p[j] + nz[j]; ++k)
			if (li[k] < n) t.emplace_back(li[k], j, lx[k]);
	return fromTriplets(n, t);
}

Eigen::SparseMatrix<double> toEigenSparse(const LowerCsc& L, int n)
{
	Triplets t;
	for (int j = 0; j < n && j < L.n; ++j)
		for (int k = L.col_ptr[j]; k < L.col_ptr[j + 1]; ++k)
			if (L.row_idx[k] < n) t.emplace_back(L.row_idx[k], j, L.values[k]);
	return fromTriplets(n, t);
}

}  // namespace esif
