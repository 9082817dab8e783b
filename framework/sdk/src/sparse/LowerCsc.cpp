#include <esif/sparse/LowerCsc.h>

namespace esif
{
void LowerCsc::truncateColumns(int columns, int rows)
{
	const int end = col_ptr[columns];
	col_ptr.resize(columns + 1);
	row_idx.resize(end);
	values.resize(end);
	n = rows;
}

void LowerCsc::appendColumns(const LowerCsc& tail, int offset)
{
	const int base = col_ptr.back();
	for (int j = 1; j <= tail.n; ++j) col_ptr.push_back(base + tail.col_ptr[j]);
	for (int r : tail.row_idx) row_idx.push_back(r + offset);
	values.insert(values.end(), tail.values.begin(), tail.values.end());
	n = offset + tail.n;
}

void LowerCsc::solveLower(Eigen::Ref<Eigen::VectorXd> b) const
{
	for (int j = 0; j < n; ++j)
	{
		const double bj = b[j] /= values[col_ptr[j]];
		for (int k = col_ptr[j] + 1; k < col_ptr[j + 1]; ++k) b[row_idx[k]] -= values[k] * bj;
	}
}

void LowerCsc::solveLowerTransposed(Eigen::Ref<Eigen::VectorXd> b) const
{
	for (int j = n - 1; j >= 0; --j)
	{
		double s = b[j];
		for (int k = col_ptr[j] + 1; k < col_ptr[j + 1]; ++k) s -= values[k] * b[row_idx[k]];
		b[j] = s / values[col_ptr[j]];
	}
}

LowerCsc LowerCsc::fromDenseLower(const Eigen::MatrixXd& S)
{
	LowerCsc out;
	out.n = static_cast<int>(S.cols());
	for (int j = 0; j < out.n; ++j)
	{
		for (int i = j; i < out.n; ++i)
			if (i == j || S(i, j) != 0.0)
			{
				out.row_idx.push_back(i);
				out.values.push_back(S(i, j));
			}
		out.col_ptr.push_back(static_cast<int>(out.row_idx.size()));
	}
	return out;
}

Eigen::MatrixXd LowerCsc::toDense() const
{
	Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
	for (int j = 0; j < n; ++j)
		for (int t = col_ptr[j]; t < col_ptr[j + 1]; ++t) M(row_idx[t], j) = values[t];
	return M;
}

}  // namespace esif
