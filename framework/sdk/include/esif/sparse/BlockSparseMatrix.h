#pragma once
/// \file BlockSparseMatrix.h
/// Symmetric block-sparse matrix stored per block column: column j holds the
/// blocks (i, j) it couples, sorted by i, both triangles. Built for frequent
/// small additive updates (I += J^T R^-1 J touches a few blocks, book eq. 3.15):
/// adding to an existing block is a short search in one small column and
/// creating one is an insertion there; no global re-compression. Compressed
/// forms (CSC in any variable ordering) are made on demand.

#include <esif/sparse/LowerCsc.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstddef>
#include <utility>
#include <vector>

namespace esif
{
class BlockSparseMatrix
{
   public:
	/// Blocks are at most 3x3 (a pose); the top-left dim(i) x dim(j) is used.
	using Block = Eigen::Matrix3d;

	/// Block (row, column) of the matrix, `column` being the owning column.
	struct Entry
	{
		int row = 0;
		Block value = Block::Zero();
	};

	/// Appends a block row and column of dimension `dim` (2 or 3) holding
	/// zeros, with its (zero) diagonal block stored; returns its block index.
	int addBlockVariable(int dim);

	int blockCount() const { return static_cast<int>(columns_.size()); }
	int blockDim(int b) const { return dim_[b]; }
	int blockOffset(int b) const { return offset_[b]; }
	int scalarDim() const { return scalar_dim_; }
	/// Block of the scalar index g.
	int blockOfScalar(int g) const { return block_of_scalar_[g]; }

	/// M(row, col) += value (dim(row) x dim(col)) and, if row != col, the
	/// transposed block too, keeping M symmetric. For row == col `value`
	/// must be symmetric.
	void addBlock(int row, int col, const Eigen::Ref<const Eigen::MatrixXd>& value);

	/// The blocks of block column b, sorted by row.
	const std::vector<Entry>& column(int b) const { return columns_[b]; }

	/// Structural non-zeros counted per scalar, both triangles.
	std::size_t nonZeros() const { return nnz_; }

	/// y = M x.
	void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

	/// The scalar diagonal of M.
	Eigen::VectorXd diagonal() const;
	/// M(g, g).
	double diagonalEntry(int g) const;

	/// Non-zeros (natural row, value) of scalar column g.
	std::vector<std::pair<int, double>> scalarColumn(int g) const;

	/// Lower triangle of P M P^T in compressed columns, where scalar g goes
	/// to `position[g]`. Scalars from scalarDim() up to `size` - 1 are
	/// identity padding rows (a 1 on the diagonal): room for variables yet
	/// to come. `position` has `size` entries.
	LowerCsc permutedLower(const std::vector<int>& position, int size) const;

	/// The whole matrix, dense (tests and small problems).
	Eigen::MatrixXd toDense() const;

   private:
	Block& blockAt(int row, int col);
	const Block& diagonalBlock(int b) const;

	std::vector<std::vector<Entry>> columns_;
	std::vector<int> dim_, offset_, block_of_scalar_;
	int scalar_dim_ = 0;
	std::size_t nnz_ = 0;
};

/// The block matrix, both triangles, natural scalar order; structurally
/// present entries are kept even when their value is zero (pictures of the
/// sparsity, book Fig. 3.12-3.13, and tests of the pattern).
Eigen::SparseMatrix<double> toEigenSparse(const BlockSparseMatrix& M);

}  // namespace esif
