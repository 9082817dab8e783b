#include "sparse/EliminationTreeSolves.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

namespace esif
{
namespace
{
struct FactorArrays
{
	const int* p;
	const int* nz;
	const int* i;
	const double* x;
	int n;

	explicit FactorArrays(const cholmod_factor& L)
		: p(static_cast<const int*>(L.p)), nz(static_cast<const int*>(L.nz)), i(static_cast<const int*>(L.i)),
		  x(static_cast<const double*>(L.x)), n(static_cast<int>(L.n))
	{
		if (L.is_super || L.is_ll || L.xtype != CHOLMOD_REAL)
			throw std::logic_error("elimination-tree solves need a real simplicial LDL^T factor");
	}
	/// Parent in the elimination tree, -1 at a root (rows sorted, diagonal first).
	int parent(int j) const { return nz[j] > 1 ? i[p[j] + 1] : -1; }
	/// Off-diagonal entries of column j: [begin, end).
	int begin(int j) const { return p[j] + 1; }
	int end(int j) const { return p[j] + nz[j]; }
	/// D(j, j): simplicialPivot() of an LDL^T factor, on the arrays cached for the solves' inner loops.
	double diagonal(int j) const { return x[p[j]]; }
};

void checkPosition(int j, int n)
{
	if (j < 0 || j >= n) throw std::out_of_range("elimination-tree solve: position outside the factor");
}

/// Walks up from each start until a position already claimed (whose
/// ancestors are claimed too), claiming the rest and appending them to `out`.
template <class Claimed, class Claim>
void appendUnclaimedPaths(const FactorArrays& f, const std::vector<int>& starts, Claimed claimed, Claim claim,
						  std::vector<int>& out)
{
	for (int j : starts)
	{
		checkPosition(j, f.n);
		for (; j >= 0 && !claimed(j); j = f.parent(j))
		{
			claim(j);
			out.push_back(j);
		}
	}
}

}  // namespace

std::vector<int> pathsToRoots(const cholmod_factor& L, const std::vector<int>& starts)
{
	const FactorArrays f(L);
	std::vector<char> reached(static_cast<std::size_t>(f.n), 0);
	std::vector<int> out;
	appendUnclaimedPaths(
		f, starts, [&](int j) { return reached[j] != 0; }, [&](int j) { reached[j] = 1; }, out);
	std::sort(out.begin(), out.end());
	return out;
}

Eigen::MatrixXd scaledForwardColumns(const cholmod_factor& L, const std::vector<int>& positions,
									 const std::vector<int>& reach)
{
	const FactorArrays f(L);
	// slot[j]: column of position j in the result (reach is ascending).
	std::vector<int> slot(static_cast<std::size_t>(f.n), -1);
	for (std::size_t c = 0; c < reach.size(); ++c) slot[reach[c]] = static_cast<int>(c);
	const auto k = static_cast<Eigen::Index>(positions.size());
	Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(k, static_cast<Eigen::Index>(reach.size()));
	for (Eigen::Index a = 0; a < k; ++a) Y(a, slot[positions[a]]) = 1.0;
	// Forward substitution, column by column: every row of column j is an
	// ancestor of j, so it is in the reach and later in it.
	for (std::size_t c = 0; c < reach.size(); ++c)
	{
		const int j = reach[c];
		const Eigen::VectorXd yj = Y.col(static_cast<Eigen::Index>(c));
		for (int t = f.begin(j); t < f.end(j); ++t) Y.col(slot[f.i[t]]) -= f.x[t] * yj;
		Y.col(static_cast<Eigen::Index>(c)) /= std::sqrt(f.diagonal(j));
	}
	return Y;
}

Eigen::VectorXd PartialBackSubstitution::solveAt(const cholmod_factor& L, const double* y,
												  const std::vector<int>& positions)
{
	const FactorArrays f(L);
	if (static_cast<int>(z_.size()) != f.n)
	{
		z_.assign(static_cast<std::size_t>(f.n), 0.0);
		stamp_.assign(static_cast<std::size_t>(f.n), 0);
		invalidate();
	}
	// A position is claimed when queued: its value is computed below, before
	// any caller can read it, and its ancestors are queued or known.
	todo_.clear();
	appendUnclaimedPaths(
		f, positions, [this](int j) { return known(j); }, [this](int j) { stamp_[j] = epoch_; }, todo_);
	// The root first: z_j = y_j / d_j - sum_i L_ij z_i over j's ancestors i.
	std::sort(todo_.begin(), todo_.end(), std::greater<>());
	for (const int j : todo_)
	{
		double zj = y[j] / f.diagonal(j);
		for (int t = f.begin(j); t < f.end(j); ++t) zj -= f.x[t] * z_[f.i[t]];
		z_[j] = zj;
	}
	columns_solved_ += static_cast<long>(todo_.size());
	Eigen::VectorXd out(static_cast<Eigen::Index>(positions.size()));
	for (std::size_t a = 0; a < positions.size(); ++a) out(static_cast<Eigen::Index>(a)) = z_[positions[a]];
	return out;
}

}  // namespace esif
