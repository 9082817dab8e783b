#include <esif/sparse/SparseCounters.h>

#include <algorithm>

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
		{prefix + "top_separator_scalars", n(top_separator_scalars)},
		{prefix + "full_reorders", n(full_reorders)},
		{prefix + "partial_refactorisations", n(partial_refactorisations)},
		{prefix + "pcg_solves", n(pcg_solves)},
		{prefix + "pcg_iterations_total", n(pcg_iterations_total)},
		{prefix + "pcg_iterations_max", n(pcg_iterations_max)},
		{prefix + "back_substitution_columns", n(back_substitution_columns)},
		{prefix + "updated_path_columns", n(updated_path_columns)},
		{prefix + "updown_flops", updown_flops},
		{prefix + "fresh_factor_flops", fresh_factor_flops},
		{prefix + "update_time_s", update_time_s},
		{prefix + "factor_time_s", factor_time_s},
		{prefix + "recovery_time_s", recovery_time_s},
	};
}

SparseCounters& SparseCounters::operator+=(const SparseCounters& part)
{
	full_reorders += part.full_reorders;
	partial_refactorisations += part.partial_refactorisations;
	pcg_solves += part.pcg_solves;
	pcg_iterations_total += part.pcg_iterations_total;
	pcg_iterations_max = std::max(pcg_iterations_max, part.pcg_iterations_max);
	back_substitution_columns += part.back_substitution_columns;
	updated_path_columns += part.updated_path_columns;
	updown_flops += part.updown_flops;
	fresh_factor_flops += part.fresh_factor_flops;
	update_time_s += part.update_time_s;
	factor_time_s += part.factor_time_s;
	recovery_time_s += part.recovery_time_s;
	return *this;
}

}  // namespace esif
