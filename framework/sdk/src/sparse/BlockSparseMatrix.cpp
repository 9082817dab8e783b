#include <esif/sparse/BlockSparseMatrix.h>

#include <algorithm>
#include <stdexcept>

namespace esif
{
int BlockSparseMatrix::addBlockVariable(int dim)
{
	if (dim < 1 || dim > 3) throw std::invalid_argument("BlockSparseMatrix: block dimension must be 1..3");
	const int b = blockCount();
	dim_.push_back(dim);
	offset_.push_back(scalar_dim_);
	for (int k = 0; k < dim; ++k) block_of_scalar_.push_back(b);
	scalar_dim_ += dim;
	// The diagonal block exists from the start (zero information, book Sec.
	// 3.1.3.3), so every compressed form has a structural diagonal.
	columns_.push_back({Entry{b, Block::Zero()}});
	nnz_ += static_cast<std::size_t>(dim * dim);
	return b;
}

BlockSparseMatrix::Block& BlockSparseMatrix::blockAt(int row, int col)
{
	auto& column = columns_[col];
	auto it = std::lower_bound(column.begin(), column.end(), row, [](const Entry& e, int r) {
		return e.row < r;
	});
	if (it != column.end() && it->row == row) return it->value;
	nnz_ += static_cast<std::size_t>(dim_[row] * dim_[col]);
	return column.insert(it, Entry{row, Block::Zero()})->value;
}

void BlockSparseMatrix::addBlock(int row, int col, const Eigen::Ref<const Eigen::MatrixXd>& value)
{
	const int dr = dim_[row], dc = dim_[col];
	if (value.rows() != dr || value.cols() != dc)
		throw std::invalid_argument("BlockSparseMatrix::addBlock: block size does not match the variables");
	blockAt(row, col).topLeftCorner(dr, dc) += value;
	if (row != col) blockAt(col, row).topLeftCorner(dc, dr) += value.transpose();
}

void BlockSparseMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const
{
	y.setZero(scalar_dim_);
	for (int j = 0; j < blockCount(); ++j)
	{
		const int dj = dim_[j], oj = offset_[j];
		for (const auto& e : columns_[j])
		{
			const int di = dim_[e.row], oi = offset_[e.row];
			for (int a = 0; a < di; ++a)
			{
				double s = 0;
				for (int b = 0; b < dj; ++b) s += e.value(a, b) * x[oj + b];
				y[oi + a] += s;
			}
		}
	}
}

const BlockSparseMatrix::Block& BlockSparseMatrix::diagonalBlock(int b) const
{
	const auto& column = columns_[b];
	// Always present: addBlockVariable stores it.
	return std::lower_bound(column.begin(), column.end(), b,
							[](const Entry& e, int r) {
								return e.row < r;
							})
		->value;
}

Eigen::VectorXd BlockSparseMatrix::diagonal() const
{
	Eigen::VectorXd d(scalar_dim_);
	for (int j = 0; j < blockCount(); ++j)
		for (int a = 0; a < dim_[j]; ++a) d[offset_[j] + a] = diagonalBlock(j)(a, a);
	return d;
}

double BlockSparseMatrix::diagonalEntry(int g) const
{
	const int b = block_of_scalar_[g], a = g - offset_[b];
	return diagonalBlock(b)(a, a);
}

std::vector<std::pair<int, double>> BlockSparseMatrix::scalarColumn(int g) const
{
	const int j = block_of_scalar_[g], b = g - offset_[j];
	std::vector<std::pair<int, double>> out;
	for (const auto& e : columns_[j])
		for (int a = 0; a < dim_[e.row]; ++a) out.emplace_back(offset_[e.row] + a, e.value(a, b));
	return out;
}

LowerCsc BlockSparseMatrix::permutedLower(const std::vector<int>& position, int size) const
{
	// Counting pass, then a filling pass, then each unsorted column sorted
	// by row: O(nnz log(column length)) at worst, done only when a factor is
	// built afresh in a permuted order (the natural order goes straight to
	// CHOLMOD: naturalLowerToCholmod).
	LowerCsc out;
	out.n = size;
	std::vector<int> count(size, 0);
	auto forEachLower = [&](auto&& emit) {
		for (int j = 0; j < blockCount(); ++j)
			for (const auto& e : columns_[j])
				for (int b = 0; b < dim_[j]; ++b)
					for (int a = 0; a < dim_[e.row]; ++a)
					{
						const int p = position[offset_[e.row] + a], q = position[offset_[j] + b];
						if (p >= q) emit(p, q, e.value(a, b));
					}
		for (int g = scalar_dim_; g < size; ++g) emit(position[g], position[g], 1.0);
	};
	forEachLower([&](int, int q, double) {
		++count[q];
	});
	out.col_ptr.assign(size + 1, 0);
	for (int q = 0; q < size; ++q) out.col_ptr[q + 1] = out.col_ptr[q] + count[q];
	out.row_idx.resize(out.col_ptr[size]);
	out.values.resize(out.col_ptr[size]);
	std::vector<int> next(out.col_ptr.begin(), out.col_ptr.end() - 1);
	forEachLower([&](int p, int q, double v) {
		out.row_idx[next[q]] = p;
		out.values[next[q]++] = v;
	});
	std::vector<std::pair<int, double>> column;
	for (int q = 0; q < size; ++q)
	{
		// Columns that come out sorted (an ordering that keeps each block
		// column's rows in order) skip the copy and the sort.
		if (std::is_sorted(out.row_idx.begin() + out.col_ptr[q], out.row_idx.begin() + out.col_ptr[q + 1])) continue;
		column.clear();
		for (int k = out.col_ptr[q]; k < out.col_ptr[q + 1]; ++k) column.emplace_back(out.row_idx[k], out.values[k]);
		std::sort(column.begin(), column.end(), [](const auto& a, const auto& b) {
			return a.first < b.first;
		});
		for (std::size_t k = 0; k < column.size(); ++k)
		{
			out.row_idx[out.col_ptr[q] + k] = column[k].first;
			out.values[out.col_ptr[q] + k] = column[k].second;
		}
	}
	return out;
}

Eigen::MatrixXd BlockSparseMatrix::toDense() const
{
	Eigen::MatrixXd M = Eigen::MatrixXd::Zero(scalar_dim_, scalar_dim_);
	for (int j = 0; j < blockCount(); ++j)
		for (const auto& e : columns_[j])
			M.block(offset_[e.row], offset_[j], dim_[e.row], dim_[j]) = e.value.topLeftCorner(dim_[e.row], dim_[j]);
	return M;
}

}  // namespace esif
