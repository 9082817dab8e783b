#include <esif/core/Errors.h>
#include "sparse/Cholmod.h"

#include <algorithm>

namespace esif
{
CholmodCommon::CholmodCommon()
{
	cholmod_start(&common_);
	common_.print = 0;
}

CholmodCommon::~CholmodCommon()
{
	cholmod_finish(&common_);
}

void CholmodCommon::useGivenOrderingForModification()
{
	common_.nmethods = 1;
	common_.method[0].ordering = CHOLMOD_GIVEN;
	common_.postorder = false;  // postordering could move the trailing variables forward
	// updown modifies only a simplicial LDL^T. CHOLMOD factors
	// supernodally (BLAS) where the analysis predicts at least
	// supernodal_switch (40) flops per non-zero of L, and converts the result,
	// dropping the relaxed supernodes' zeros (final_resymbol): the filters'
	// small factors stay simplicial (a supernodal factorisation converted
	// cost more there, docs/plugins/slsjf.md "Recovery"); on a 150,000-step
	// prefix of the 100k city (60k landmarks) the fresh factorisations went
	// 458 -> 340 s of a 568 s replay, same factor and estimate
	// (docs/sparse-core.md, "At city scale").
	common_.supernodal = CHOLMOD_AUTO;
	common_.final_resymbol = true;
	common_.final_asis = false;
	common_.final_super = false;
	common_.final_ll = false;
	common_.final_pack = false;  // leave slack in each column for the fill of later updates
	common_.final_monotonic = true;
}

void CholmodCommon::useFillReducingOrdering()
{
	common_.nmethods = 1;
	common_.method[0].ordering = CHOLMOD_AMD;
	common_.postorder = true;
	common_.supernodal = CHOLMOD_AUTO;
	common_.final_asis = true;
	common_.final_pack = true;
}

namespace
{
const char* statusText(int status)
{
	switch (status)
	{
		case CHOLMOD_NOT_INSTALLED:
			return "method not installed";
		case CHOLMOD_OUT_OF_MEMORY:
			return "out of memory";
		case CHOLMOD_TOO_LARGE:
			return "problem too large (integer overflow)";
		case CHOLMOD_INVALID:
			return "invalid input";
		case CHOLMOD_NOT_POSDEF:
			return "matrix not positive definite";
		case CHOLMOD_DSMALL:
			return "tiny pivot";
		default:
			return "unknown status";
	}
}
}  // namespace

void CholmodCommon::check(const std::string& what)
{
	if (common_.status >= CHOLMOD_OK) return;
	throw NumericalError(what + ": CHOLMOD " + statusText(common_.status) + " (status " +
						 std::to_string(common_.status) + ")");
}

template <>
void CholmodDeleter<cholmod_sparse>::operator()(cholmod_sparse* p) const
{
	cholmod_free_sparse(&p, common);
}

template <>
void CholmodDeleter<cholmod_factor>::operator()(cholmod_factor* p) const
{
	cholmod_free_factor(&p, common);
}

template <>
void CholmodDeleter<cholmod_dense>::operator()(cholmod_dense* p) const
{
	cholmod_free_dense(&p, common);
}

CholmodSparsePtr ownSparse(cholmod_sparse* p, CholmodCommon& c)
{
	return CholmodSparsePtr(p, CholmodDeleter<cholmod_sparse>{c.get()});
}

CholmodFactorPtr ownFactor(cholmod_factor* p, CholmodCommon& c)
{
	return CholmodFactorPtr(p, CholmodDeleter<cholmod_factor>{c.get()});
}

CholmodDensePtr ownDense(cholmod_dense* p, CholmodCommon& c)
{
	return CholmodDensePtr(p, CholmodDeleter<cholmod_dense>{c.get()});
}

CholmodDensePtr zeroDense(std::size_t rows, std::size_t cols, CholmodCommon& c)
{
	auto d = ownDense(cholmod_zeros(rows, cols, CHOLMOD_REAL, c.get()), c);
	if (!d) c.check("allocating a dense CHOLMOD matrix");
	return d;
}

CholmodSparsePtr toCholmod(const LowerCsc& A, CholmodCommon& c)
{
	auto S = ownSparse(cholmod_allocate_sparse(A.n, A.n, A.nonZeros(), true, true, -1, CHOLMOD_REAL, c.get()), c);
	if (!S) c.check("allocating a sparse CHOLMOD matrix");
	std::copy(A.col_ptr.begin(), A.col_ptr.end(), static_cast<int*>(S->p));
	std::copy(A.row_idx.begin(), A.row_idx.end(), static_cast<int*>(S->i));
	std::copy(A.values.begin(), A.values.end(), static_cast<double*>(S->x));
	return S;
}

CholmodSparsePtr naturalLowerToCholmod(const BlockSparseMatrix& M, int size, CholmodCommon& c)
{
	// Scalar column offset(j) + b holds, for each block (i, j) with i >= j in
	// row order, the rows offset(i) + a, a from b on for the diagonal block:
	// sorted by construction. Counted from the block pattern, then filled.
	const int n = M.scalarDim();
	std::vector<int> count(size, 1);  // padding columns: their diagonal 1
	for (int j = 0; j < M.blockCount(); ++j)
	{
		int below = 0;
		for (const auto& e : M.column(j))
			if (e.row > j) below += M.blockDim(e.row);
		for (int b = 0; b < M.blockDim(j); ++b) count[M.blockOffset(j) + b] = below + M.blockDim(j) - b;
	}
	std::size_t nnz = 0;
	for (const int k : count) nnz += static_cast<std::size_t>(k);
	auto S = ownSparse(cholmod_allocate_sparse(size, size, nnz, true, true, -1, CHOLMOD_REAL, c.get()), c);
	if (!S) c.check("allocating a sparse CHOLMOD matrix");
	auto* p = static_cast<int*>(S->p);
	auto* ri = static_cast<int*>(S->i);
	auto* x = static_cast<double*>(S->x);
	p[0] = 0;
	for (int q = 0; q < size; ++q) p[q + 1] = p[q] + count[q];
	for (int j = 0; j < M.blockCount(); ++j)
		for (int b = 0; b < M.blockDim(j); ++b)
		{
			int k = p[M.blockOffset(j) + b];
			for (const auto& e : M.column(j))
			{
				if (e.row < j) continue;
				for (int a = e.row == j ? b : 0; a < M.blockDim(e.row); ++a, ++k)
				{
					ri[k] = M.blockOffset(e.row) + a;
					x[k] = e.value(a, b);
				}
			}
		}
	for (int g = n; g < size; ++g)
	{
		ri[p[g]] = g;
		x[p[g]] = 1.0;
	}
	return S;
}

void cholmodSolve(int sys, cholmod_factor* L, cholmod_dense* B, CholmodDensePtr& X, CholmodSolveWorkspace& ws,
				  CholmodCommon& c, const std::string& what)
{
	// cholmod_solve2 (re)allocates through raw handles; ownership goes back
	// to the smart pointers straight after the call.
	cholmod_dense* x = X.release();
	cholmod_dense* y = ws.y.release();
	cholmod_dense* e = ws.e.release();
	const int ok = cholmod_solve2(sys, L, B, nullptr, &x, nullptr, &y, &e, c.get());
	X = ownDense(x, c);
	ws.y = ownDense(y, c);
	ws.e = ownDense(e, c);
	if (!ok)
	{
		c.check(what);
		throw NumericalError(what + ": CHOLMOD solve failed (status " + std::to_string(c->status) + ")");
	}
}

std::vector<double> factorPivots(const cholmod_factor& L)
{
	std::vector<double> d(L.n);
	if (!L.is_super)
	{
		for (std::size_t j = 0; j < L.n; ++j) d[j] = simplicialPivot(L, static_cast<int>(j));
		return d;
	}
	const auto* x = static_cast<const double*>(L.x);
	// Supernodal: supernode s holds columns super[s]..super[s+1]-1 as a dense
	// column-major block of nsrow rows starting at x[px[s]].
	const auto* super = static_cast<const int*>(L.super);
	const auto* pi = static_cast<const int*>(L.pi);
	const auto* px = static_cast<const int*>(L.px);
	for (std::size_t s = 0; s < L.nsuper; ++s)
	{
		const int nsrow = pi[s + 1] - pi[s];
		for (int j = super[s]; j < super[s + 1]; ++j)
		{
			const int k = j - super[s];
			const double ljj = x[px[s] + k * nsrow + k];
			d[j] = ljj * ljj;
		}
	}
	return d;
}

std::size_t countFactorNonZeros(const cholmod_factor& L, std::size_t columns)
{
	std::size_t nnz = 0;
	if (!L.is_super)
	{
		const auto* nz = static_cast<const int*>(L.nz);
		for (std::size_t j = 0; j < columns && j < L.n; ++j) nnz += nz[j];
		return nnz;
	}
	const auto* super = static_cast<const int*>(L.super);
	const auto* pi = static_cast<const int*>(L.pi);
	for (std::size_t s = 0; s < L.nsuper; ++s)
	{
		const int nsrow = pi[s + 1] - pi[s];
		for (int j = super[s]; j < super[s + 1] && static_cast<std::size_t>(j) < columns; ++j)
			nnz += nsrow - (j - super[s]);
	}
	return nnz;
}

int denseTrailingColumns(const cholmod_factor& L, int columns)
{
	if (L.is_super || !L.nz) return 0;
	const auto* nz = static_cast<const int*>(L.nz);
	int dense = 0;
	for (int j = std::min(columns, static_cast<int>(L.n)) - 1; j >= 0 && nz[j] == dense + 1; --j) ++dense;
	return dense;
}

}  // namespace esif
