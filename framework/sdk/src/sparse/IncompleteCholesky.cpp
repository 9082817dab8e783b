#include "sparse/IncompleteCholesky.h"

#include <algorithm>
#include <cmath>

namespace esif
{
namespace
{
/// Finished columns k waiting to update a later column: list[r] links the
/// columns whose next unused entry is in row r (as in CSparse's left-looking
/// factorisations), so column j visits only the columns with L(j, k) != 0.
class PendingColumns
{
   public:
	explicit PendingColumns(int n) : head_(n, -1), next_(n, -1), cursor_(n, 0) {}

	/// Queues column k whose next unused entry is at `index`, row `row`.
	void push(int k, int index, int row)
	{
		cursor_[k] = index;
		next_[k] = head_[row];
		head_[row] = k;
	}
	/// Takes the whole list of row j.
	int take(int j)
	{
		const int k = head_[j];
		head_[j] = -1;
		return k;
	}
	int next(int k) const { return next_[k]; }
	int cursor(int k) const { return cursor_[k]; }

   private:
	std::vector<int> head_, next_, cursor_;
};
}  // namespace

IncompleteCholeskyResult incompleteCholesky(const LowerCsc& A, double drop_tolerance, double min_pivot_ratio)
{
	const int n = A.n;
	IncompleteCholeskyResult out;
	LowerCsc& L = out.L;
	L.n = n;
	L.col_ptr.assign(1, 0);
	std::vector<double> w(n, 0.0);
	std::vector<int> mark(n, -1), pattern;
	PendingColumns pending(n);

	for (int j = 0; j < n; ++j)
	{
		// w = A(j:n, j), with its pattern.
		pattern.clear();
		double a_jj = 0, norm1 = 0;
		for (int t = A.col_ptr[j]; t < A.col_ptr[j + 1]; ++t)
		{
			const int i = A.row_idx[t];
			if (i < j) continue;
			if (i == j) a_jj = A.values[t];
			w[i] = A.values[t];
			mark[i] = j;
			if (i > j) pattern.push_back(i);
			norm1 += std::abs(A.values[t]);
		}
		// w -= L(j:n, k) L(j, k) for every earlier column k with L(j, k) != 0.
		for (int k = pending.take(j); k >= 0;)
		{
			const int next_k = pending.next(k);
			const int start = pending.cursor(k), end = L.col_ptr[k + 1];
			const double ljk = L.values[start];
			for (int t = start; t < end; ++t)
			{
				const int i = L.row_idx[t];
				if (mark[i] != j)
				{
					mark[i] = j;
					w[i] = 0;
					if (i > j) pattern.push_back(i);
				}
				w[i] -= L.values[t] * ljk;
			}
			if (start + 1 < end) pending.push(k, start + 1, L.row_idx[start + 1]);
			k = next_k;
		}
		const double d = mark[j] == j ? w[j] : 0.0;
		out.pivots.push_back(d);
		if (!(d > 0) || !(a_jj > 0) || d < min_pivot_ratio * a_jj)
		{
			out.ok = false;
			return out;
		}
		// Column j: diagonal first, then the kept rows in ascending order.
		const double ljj = std::sqrt(d), drop = drop_tolerance * norm1 / std::sqrt(a_jj);
		std::sort(pattern.begin(), pattern.end());
		L.row_idx.push_back(j);
		L.values.push_back(ljj);
		const int first_off = static_cast<int>(L.row_idx.size());
		for (int i : pattern)
		{
			const double lij = w[i] / ljj;
			if (std::abs(lij) >= drop && lij != 0.0)
			{
				L.row_idx.push_back(i);
				L.values.push_back(lij);
			}
		}
		L.col_ptr.push_back(static_cast<int>(L.row_idx.size()));
		if (first_off < L.col_ptr[j + 1]) pending.push(j, first_off, L.row_idx[first_off]);
	}
	return out;
}

}  // namespace esif
