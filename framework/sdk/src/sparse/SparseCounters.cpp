#include <esif/sparse/SparseCounters.h>

namespace esif
{
std::vector<std::pair<std::string, double>> SparseCounters::list(const std::string& prefix) const
{
	auto n = [](std::size_t v) {
		return static_cast<double>(v);
	};
	return {
		{prefix + "information_nnz", n(information_nnz)},
		{prefix + "factor_nnz", n(factor_nnz)},
		{prefix + "full_reorders", n(full_reorders)},
		{prefix + "partial_refactorisations", n(partial_refactorisations)},
		{prefix + "pcg_solves", n(pcg_solves)},
		{prefix + "pcg_iterations_total", n(pcg_iterations_total)},
		{prefix + "pcg_iterations_max", n(pcg_iterations_max)},
		{prefix + "back_substitution_columns", n(back_substitution_columns)},
		{prefix + "update_time_s", update_time_s},
		{prefix + "factor_time_s", factor_time_s},
		{prefix + "recovery_time_s", recovery_time_s},
	};
}

}  // namespace esif
