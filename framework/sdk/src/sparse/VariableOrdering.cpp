#include <esif/core/Errors.h>
#include "sparse/VariableOrdering.h"

#include <algorithm>
#include <numeric>

namespace esif
{
void ScalarOrdering::append(int g)
{
	if (static_cast<int>(position.size()) <= g) position.resize(g + 1, -1);
	position[g] = static_cast<int>(order.size());
	order.push_back(g);
}

namespace
{
/// Variables sorted by distance from `reference`, nearest first.
std::vector<VarId> byIncreasingDistance(const InformationForm& info, const Eigen::Vector2d& reference)
{
	const int n = info.variableCount();
	std::vector<double> d2(n);
	std::vector<VarId> vars(n);
	for (int v = 0; v < n; ++v)
	{
		vars[v] = VarId{v};
		d2[v] = (info.position(vars[v]) - reference).squaredNorm();
	}
	std::stable_sort(vars.begin(), vars.end(), [&](VarId a, VarId b) {
		return d2[a.value] < d2[b.value];
	});
	return vars;
}

/// A CHOLMOD ordering reported failure: its error, or a generic one if it
/// left no status (its permutation is scratch then, never to be used).
[[noreturn]] void failed(const std::string& what, CholmodCommon& c)
{
	c.check(what);
	throw NumericalError(what + ": CHOLMOD failed");
}

/// A permutation of variable indices as the variables it orders.
std::vector<VarId> asVariables(const std::vector<int>& perm)
{
	std::vector<VarId> vars(perm.size());
	for (std::size_t k = 0; k < perm.size(); ++k) vars[k] = VarId{perm[k]};
	return vars;
}

/// Lower-triangular pattern of the variable graph (one node per variable).
CholmodSparsePtr variableGraph(const InformationForm& info, CholmodCommon& c)
{
	const auto& I = info.matrix();
	const int n = I.blockCount();
	std::size_t nnz = 0;
	for (int j = 0; j < n; ++j) nnz += I.column(j).size();
	auto A = ownSparse(cholmod_allocate_sparse(n, n, nnz, true, true, -1, CHOLMOD_PATTERN, c.get()), c);
	if (!A) c.check("reordering: allocating the variable graph");
	auto* p = static_cast<int*>(A->p);
	auto* i = static_cast<int*>(A->i);
	int k = 0;
	for (int j = 0; j < n; ++j)
	{
		p[j] = k;
		for (const auto& e : I.column(j))  // sorted rows; keep the lower part
			if (e.row >= j) i[k++] = e.row;
	}
	p[n] = k;
	return A;
}
/// The variables in the order a CHOLMOD ordering of the variable graph
/// gives: `order(A, perm)` writes the permutation and returns false when
/// CHOLMOD failed.
template <class Order>
std::vector<VarId> orderVariableGraph(const InformationForm& info, const std::string& what, CholmodCommon& c,
									  Order order)
{
	auto A = variableGraph(info, c);
	std::vector<int> perm(static_cast<std::size_t>(info.variableCount()));
	if (!order(A.get(), perm.data())) failed(what, c);
	return asVariables(perm);
}
}  // namespace

std::vector<VarId> orderByDistance(const InformationForm& info, const Eigen::Vector2d& reference)
{
	auto vars = byIncreasingDistance(info, reference);
	std::reverse(vars.begin(), vars.end());
	return vars;
}

std::vector<VarId> orderByCamd(const InformationForm& info, const Eigen::Vector2d& reference, int set_dim,
							   int near_sets, CholmodCommon& c)
{
	const int n = info.variableCount();
	if (n == 0) return {};
	// Constraint sets: nearest variables in the last set (near_sets), the
	// next ones in the set before, ...; CAMD keeps set k before set k+1.
	std::vector<int> member(n, 0);
	int filled = 0;
	for (VarId v : byIncreasingDistance(info, reference))
	{
		const int ring = filled / std::max(1, set_dim);
		if (ring >= near_sets) break;
		member[v.value] = near_sets - ring;
		filled += info.dim(v);
	}
	// CAMD wants set numbers below n: renumber the sets in use 0, 1, 2, ...
	std::vector<int> used(near_sets + 1, 0);
	for (int m : member) used[m] = 1;
	std::partial_sum(used.begin(), used.end(), used.begin());
	for (int& m : member) m = used[m] - 1;
	return orderVariableGraph(info, "CAMD ordering", c, [&](cholmod_sparse* A, int* perm) {
		return cholmod_camd(A, nullptr, 0, member.data(), perm, c.get()) != 0;
	});
}

std::vector<VarId> orderByAmd(const InformationForm& info, CholmodCommon& c)
{
	const int n = info.variableCount();
	if (n == 0) return {};
	return orderVariableGraph(info, "AMD ordering", c, [&](cholmod_sparse* A, int* perm) {
		return cholmod_amd(A, nullptr, 0, perm, c.get()) != 0;
	});
}

std::vector<VarId> orderByNestedDissection(const InformationForm& info, CholmodCommon& c)
{
	const int n = info.variableCount();
	if (n == 0) return {};
	std::vector<int> parent(n), member(n);  // the separator tree, not needed here
	return orderVariableGraph(info, "nested-dissection ordering", c, [&](cholmod_sparse* A, int* perm) {
		return cholmod_nested_dissection(A, nullptr, 0, perm, parent.data(), member.data(), c.get()) >= 0;
	});
}

std::vector<VarId> reorderVariables(const InformationForm& info, const Eigen::Vector2d& reference,
									const SparseRecoveryParams& params, CholmodCommon& c)
{
	if (params.reordering == Reordering::Amd) return orderByAmd(info, c);
	if (params.reordering == Reordering::NestedDissection) return orderByNestedDissection(info, c);
	if (params.reordering == Reordering::Camd)
		return orderByCamd(info, reference, std::max(1, params.n0 / 2), params.camd_near_sets, c);
	return orderByDistance(info, reference);
}

ScalarOrdering expandOrdering(const InformationForm& info, const std::vector<VarId>& vars, int size)
{
	ScalarOrdering s;
	s.order.reserve(size);
	s.position.assign(size, -1);
	for (VarId v : vars)
		for (int a = 0; a < info.dim(v); ++a) s.append(info.offset(v) + a);
	for (int g = info.scalarDim(); g < size; ++g) s.append(g);
	return s;
}

}  // namespace esif
