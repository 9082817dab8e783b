#include <esif/core/Errors.h>
#include "sparse/SparseInverse.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace esif
{
SparseInverse::SparseInverse(const cholmod_factor& L, CholmodCommon& c)
{
	if (L.xtype != CHOLMOD_REAL) throw std::invalid_argument("SparseInverse: the factor is not numeric");
	if (L.is_super || L.is_ll)
	{
		auto copy = ownFactor(cholmod_copy_factor(const_cast<cholmod_factor*>(&L), c.get()), c);
		if (!copy) c.check("sparse inverse: copying the factor");
		cholmod_change_factor(CHOLMOD_REAL, false, false, true, true, copy.get(), c.get());
		c.check("sparse inverse: converting the factor to simplicial LDL^T");
		copyPattern(*copy);
	}
	else
		copyPattern(L);
	recurse();
}

void SparseInverse::copyPattern(const cholmod_factor& L)
{
	// Simplicial LDL^T: column j starts with d_j, then L(i, j) for i > j,
	// rows ascending; columns may be scattered (after updates) and carry
	// slack, hence p[j] and nz[j] rather than p[j + 1].
	const int n = static_cast<int>(L.n);
	const auto* p = static_cast<const int*>(L.p);
	const auto* nz = static_cast<const int*>(L.nz);
	const auto* li = static_cast<const int*>(L.i);
	const auto* lx = static_cast<const double*>(L.x);
	const auto* perm = static_cast<const int*>(L.Perm);
	col_ptr_.assign(1, 0);
	d_.resize(n);
	position_.resize(n);
	for (int j = 0; j < n; ++j)
	{
		position_[perm[j]] = j;
		d_[j] = lx[p[j]];
		for (int t = p[j]; t < p[j] + nz[j]; ++t)
		{
			row_idx_.push_back(li[t]);
			l_.push_back(t == p[j] ? 1.0 : lx[t]);
		}
		col_ptr_.push_back(static_cast<int>(row_idx_.size()));
	}
}

void SparseInverse::recurse()
{
	const int n = static_cast<int>(d_.size());
	z_.assign(row_idx_.size(), 0.0);
	std::vector<int> where(n, -1);  // local index of a row of column j
	std::vector<double> acc;
	for (int j = n - 1; j >= 0; --j)
	{
		const int first = col_ptr_[j] + 1, end = col_ptr_[j + 1], len = end - first;
		for (int t = first; t < end; ++t) where[row_idx_[t]] = t - first;
		acc.assign(len, 0.0);  // acc[i] = sum_k L_kj Z_ik, i in S_j
		for (int t = first; t < end; ++t)
		{
			// Column k of Z (k in S_j) holds Z(r, k) for r >= k; its entries
			// with r in S_j serve both acc[r] (term k) and, when r > k,
			// acc[k] (term r, by symmetry Z_kr = Z_rk).
			const int k = row_idx_[t];
			const double l_kj = l_[t];
			int found = 0;
			for (int u = col_ptr_[k]; u < col_ptr_[k + 1]; ++u)
			{
				const int r = row_idx_[u];
				if (where[r] < 0) continue;
				++found;
				acc[where[r]] += l_kj * z_[u];
				if (r > k) acc[where[k]] += l_[first + where[r]] * z_[u];
			}
			if (found != end - t)
				throw NumericalError("sparse inverse: the factor's pattern is not closed at column " +
									 std::to_string(j));
		}
		double zjj = 1.0 / d_[j];
		for (int t = first; t < end; ++t)
		{
			z_[t] = -acc[t - first];
			zjj -= l_[t] * z_[t];
			where[row_idx_[t]] = -1;
		}
		z_[col_ptr_[j]] = zjj;
	}
}

int SparseInverse::find(int row, int col) const
{
	const auto begin = row_idx_.begin() + col_ptr_[col], end = row_idx_.begin() + col_ptr_[col + 1];
	const auto it = std::lower_bound(begin, end, row);
	return it != end && *it == row ? static_cast<int>(it - row_idx_.begin()) : -1;
}

bool SparseInverse::contains(int g, int h) const
{
	const int a = position_[g], b = position_[h];
	return find(std::max(a, b), std::min(a, b)) >= 0;
}

double SparseInverse::at(int g, int h) const
{
	const int a = position_[g], b = position_[h];
	const int k = find(std::max(a, b), std::min(a, b));
	if (k < 0) throw std::out_of_range("SparseInverse: entry outside the factor's pattern");
	return z_[k];
}

Eigen::MatrixXd SparseInverse::block(const std::vector<int>& scalars) const
{
	const int m = static_cast<int>(scalars.size());
	Eigen::MatrixXd B(m, m);
	for (int a = 0; a < m; ++a)
		for (int b = 0; b <= a; ++b) B(a, b) = B(b, a) = at(scalars[a], scalars[b]);
	return B;
}

}  // namespace esif
