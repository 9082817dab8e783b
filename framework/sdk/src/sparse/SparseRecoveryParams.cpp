#include <esif/sparse/SparseRecoveryParams.h>

namespace esif
{
namespace
{
const std::vector<std::pair<std::string, RecoveryMethod>> kRecoveryNames = {
	{"incremental_cholesky", RecoveryMethod::IncrementalCholesky},
	{"pcg", RecoveryMethod::Pcg},
	{"fresh_cholesky", RecoveryMethod::FreshCholesky}};

const std::vector<std::pair<std::string, Reordering>> kReorderingNames = {{"distance", Reordering::Distance},
																		  {"camd", Reordering::Camd},
																		  {"amd", Reordering::Amd},
																		  {"nested_dissection", Reordering::NestedDissection}};
const std::vector<std::pair<std::string, ReorderTrigger>> kTriggerNames = {
	{"trailing_dimension", ReorderTrigger::TrailingDimension}, {"fill_growth", ReorderTrigger::FillGrowth}};

/// INI name of `value` in `table`, "?" if it has none.
template <class E>
const char* nameIn(const std::vector<std::pair<std::string, E>>& table, E value)
{
	for (const auto& [name, v] : table)
		if (v == value) return name.c_str();
	return "?";
}
}  // namespace

void SparseRecoveryParams::declare(ParamBinder& b)
{
	b.enumeration<RecoveryMethod>(
		"recovery", recovery, kRecoveryNames,
		"state/covariance recovery: incremental complete Cholesky (CHOLMOD), PCG with an incremental "
		"incomplete-Cholesky preconditioner, or a fresh AMD factorisation at every change");
	b.enumeration<Reordering>(
		"reordering", reordering, kReorderingNames,
		"reordering when the factor is rebuilt: by distance from the reference point (book), CAMD with "
		"the nearest variables constrained last, or with no constraint (for fill_growth) AMD or nested "
		"dissection (METIS separators: less fill than AMD on large two-dimensional maps)");
	b.integer("n0", n0, "trailing dimension of an update at which the state is reordered and factored afresh",
			  Bounds::atLeast(1));
	b.integer("camd_near_sets", camd_near_sets, "CAMD constraint sets of about n0/2 scalars for the nearest variables",
			  Bounds::atLeast(1));
	b.enumeration<ReorderTrigger>(
		"reorder_trigger", reorder_trigger, kTriggerNames,
		"when the incremental Cholesky factor is reordered and rebuilt: an update n0 scalars from the end of the "
		"ordering (book), or fill-in beyond max_fill_growth (incremental_cholesky only; pcg keeps n0)");
	b.real("max_fill_growth", max_fill_growth,
		   "fill_growth: rebuild when nnz(L) exceeds (1 + this) x the fresh factor's, scaled by the state's growth",
		   Bounds::positive());
	b.real("pcg_relative_tolerance", pcg_relative_tolerance, "PCG stops at |I x - b| <= this * |b|",
		   Bounds::openUnit());
	b.integer("pcg_max_iterations", pcg_max_iterations, "PCG iterations before giving up", Bounds::atLeast(1));
	b.real("ic_drop_tolerance", ic_drop_tolerance, "incomplete-Cholesky drop tolerance, relative to the column",
		   Bounds::closed(0, 1));
	b.real("min_pivot_ratio", min_pivot_ratio, "smallest accepted pivot / diagonal ratio before declaring I singular",
		   Bounds::openUnit());
}

const char* recoveryMethodName(RecoveryMethod m) { return nameIn(kRecoveryNames, m); }

const char* reorderTriggerName(ReorderTrigger t) { return nameIn(kTriggerNames, t); }

const char* reorderingName(Reordering r) { return nameIn(kReorderingNames, r); }

const char* reorderingTitle(Reordering r)
{
	switch (r)
	{
		case Reordering::Distance: return "distance reordering";
		case Reordering::Camd: return "CAMD reordering";
		case Reordering::Amd: return "AMD reordering";
		case Reordering::NestedDissection: return "nested-dissection reordering";
	}
	return "?";
}

}  // namespace esif
