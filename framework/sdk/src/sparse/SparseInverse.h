#pragma once
/// \file SparseInverse.h
/// The entries of A^-1 on the non-zero pattern of its Cholesky factor,
/// without forming the inverse: the Takahashi recursion (Takahashi, Fagan &
/// Chen 1973; Erisman & Tinney 1975) on a simplicial LDL^T factor of
/// P A P^T. With Z = (P A P^T)^-1 and S_j the rows below the diagonal of
/// column j of L, from the last column to the first:
///   Z_ij = - sum_{k in S_j} L_kj Z_ik          (i in S_j)
///   Z_jj = 1 / d_j - sum_{k in S_j} L_kj Z_kj
/// Every Z_ik needed lies in the pattern (S_j is a clique of the filled
/// graph), so the cost is about sum_j |S_j|^2, the cost of a factorisation,
/// and all diagonal blocks of A^-1 (every landmark's 2x2, every pose's 3x3
/// marginal covariance) come out of one pass instead of one solve each.

#include "sparse/Cholmod.h"

#include <Eigen/Core>
#include <vector>

namespace esif
{
class SparseInverse
{
   public:
	/// Runs the recursion on `L` (any numeric CHOLMOD factor; supernodal or
	/// LL^T factors are converted on a copy to simplicial LDL^T).
	SparseInverse(const cholmod_factor& L, CholmodCommon& c);

	/// True if (A^-1)(g, h) (natural indices) lies in the factor's pattern.
	bool contains(int g, int h) const;
	/// (A^-1)(g, h); throws std::out_of_range outside the pattern.
	double at(int g, int h) const;
	/// The block of A^-1 on the natural indices `scalars` (all pairs must
	/// lie in the pattern, as they do within one variable).
	Eigen::MatrixXd block(const std::vector<int>& scalars) const;

	/// Structural non-zeros computed (lower triangle with diagonal).
	std::size_t nonZeros() const { return row_idx_.size(); }

   private:
	void copyPattern(const cholmod_factor& L);
	void recurse();
	int find(int row, int col) const;  ///< index in the arrays, or -1 (positions, row >= col)

	std::vector<int> col_ptr_, row_idx_, position_;
	std::vector<double> l_, d_, z_;
};

}  // namespace esif
