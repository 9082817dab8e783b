#pragma once
/// \file Cholmod.h
/// RAII ownership of CHOLMOD objects (SuiteSparse 5.12, int API). Every
/// cholmod_sparse / cholmod_factor / cholmod_dense lives in a unique_ptr whose
/// deleter frees it through the cholmod_common it was made with, so no owning
/// raw pointer appears anywhere else. One CholmodCommon per sparse core: it
/// must outlive every object made with it (declare it first in the owner).

#include <esif/sparse/BlockSparseMatrix.h>
#include <esif/sparse/LowerCsc.h>

#include <cholmod.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace esif
{
/// Owns one started cholmod_common; non-copyable and non-movable because the
/// objects made with it keep its address in their deleters.
class CholmodCommon
{
   public:
	/// cholmod_start with printing off: esif reports failures itself.
	CholmodCommon();
	~CholmodCommon();
	CholmodCommon(const CholmodCommon&) = delete;
	CholmodCommon& operator=(const CholmodCommon&) = delete;

	cholmod_common* get() { return &common_; }
	cholmod_common* operator->() { return &common_; }

	/// Settings for factors that will be modified (updown/rowadd): simplicial
	/// LDL^T with room to grow, analysed with the given permutation as is
	/// (no postordering, so "last in the ordering" stays last).
	void useGivenOrderingForModification();
	/// Settings for a one-off factorisation: AMD with postordering, supernodal
	/// when CHOLMOD judges it faster.
	void useFillReducingOrdering();

	/// Throws NumericalError "<what>: CHOLMOD <status text>" if the last call
	/// failed (negative status). Warnings (not positive definite, tiny pivot)
	/// pass: the pivot check names the variable at fault (PivotCheck.h).
	void check(const std::string& what);

   private:
	cholmod_common common_;
};

/// Deleter of a CHOLMOD object of type T (sparse, factor or dense).
template <class T>
struct CholmodDeleter
{
	cholmod_common* common = nullptr;
	void operator()(T* p) const;
};

using CholmodSparsePtr = std::unique_ptr<cholmod_sparse, CholmodDeleter<cholmod_sparse>>;
using CholmodFactorPtr = std::unique_ptr<cholmod_factor, CholmodDeleter<cholmod_factor>>;
using CholmodDensePtr = std::unique_ptr<cholmod_dense, CholmodDeleter<cholmod_dense>>;

/// Takes ownership of objects returned by CHOLMOD (null stays null).
CholmodSparsePtr ownSparse(cholmod_sparse* p, CholmodCommon& c);
CholmodFactorPtr ownFactor(cholmod_factor* p, CholmodCommon& c);
CholmodDensePtr ownDense(cholmod_dense* p, CholmodCommon& c);

/// A zero dense matrix of the given size.
CholmodDensePtr zeroDense(std::size_t rows, std::size_t cols, CholmodCommon& c);

/// A symmetric CHOLMOD matrix (lower triangle stored) copied from `A`.
CholmodSparsePtr toCholmod(const LowerCsc& A, CholmodCommon& c);

/// The lower triangle of M in its natural scalar order, bordered up to
/// `size` by identity padding rows, written straight into a symmetric CHOLMOD
/// matrix with sorted columns: what M.permutedLower(identity, size) and
/// toCholmod give, without the intermediate copy, the position lookups and
/// the sort checks (a fresh factorisation's largest cost of its own).
CholmodSparsePtr naturalLowerToCholmod(const BlockSparseMatrix& M, int size, CholmodCommon& c);

/// Workspace reused by cholmodSolve between calls (cholmod_solve2's Y and E).
struct CholmodSolveWorkspace
{
	CholmodDensePtr y, e;
};

/// X = solution of system `sys` (CHOLMOD_A, CHOLMOD_L, CHOLMOD_P, ...) with
/// factor L and right-hand side B, reusing X's storage and `ws`; throws
/// NumericalError naming `what` on failure.
void cholmodSolve(int sys, cholmod_factor* L, cholmod_dense* B, CholmodDensePtr& X, CholmodSolveWorkspace& ws,
				  CholmodCommon& c, const std::string& what);

/// The pivots d_j of a simplicial or supernodal factor of
/// P A P^T = L D L^T (for an LL^T factor, d_j = L_jj^2), in factor order.
std::vector<double> factorPivots(const cholmod_factor& L);
/// Pivot j of a simplicial factor: D(j, j) of LDL^T, L(j, j)^2 of LL^T. A
/// simplicial column starts with its diagonal entry.
inline double simplicialPivot(const cholmod_factor& L, int j)
{
	const double ljj = static_cast<const double*>(L.x)[static_cast<const int*>(L.p)[j]];
	return L.is_ll ? ljj * ljj : ljj;
}

/// Structural non-zeros of a numeric factor (lower triangle with diagonal),
/// over its leading `columns` columns.
std::size_t countFactorNonZeros(const cholmod_factor& L, std::size_t columns);

/// How many of the last of the leading `columns` columns of a simplicial
/// factor form a full lower triangle: the root separator of the elimination
/// tree, which every update's path ends in, when the tree has one root (0
/// for a supernodal or symbolic factor).
int denseTrailingColumns(const cholmod_factor& L, int columns);

}  // namespace esif
