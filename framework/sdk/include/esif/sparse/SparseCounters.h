#pragma once
/// \file SparseCounters.h
/// Cost counters of the sparse information core, for a plugin to copy into
/// esif::CostFigures::counters.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace esif
{
struct SparseCounters
{
	std::size_t information_nnz = 0;  ///< structural non-zeros of I (both triangles)
	std::size_t factor_nnz = 0;       ///< non-zeros of the Cholesky factor or IC preconditioner (lower triangle)
	/// Scalars of the elimination tree's root separator (the factor's dense
	/// trailing triangle) at the last fresh factorisation of the incremental
	/// Cholesky; every update's path ends in it.
	std::size_t top_separator_scalars = 0;
	std::size_t full_reorders = 0;    ///< reorderings with a factorisation from scratch (Case ii)
	std::size_t partial_refactorisations = 0;  ///< trailing-part refactorisations (Case i)
	std::size_t pcg_solves = 0;                ///< PCG solves (state and covariance columns)
	std::size_t pcg_iterations_total = 0;      ///< PCG iterations over all solves
	std::size_t pcg_iterations_max = 0;        ///< most PCG iterations of one solve
	std::size_t back_substitution_columns = 0;  ///< factor columns solved for the state (eq. 3.37), whole or on demand
	/// Factor columns an incremental refactorisation modified: the union of
	/// the elimination-tree paths of the rows it touched, summed over the
	/// partial refactorisations. Its mean per refactorisation is how much of
	/// the tree an update reaches (every path ends in the top separators).
	std::size_t updated_path_columns = 0;
	double updown_flops = 0;        ///< CHOLMOD's flop count of every update/downdate (Common->modfl), summed
	double fresh_factor_flops = 0;  ///< CHOLMOD's predicted flops of every fresh factorisation (Common->fl), summed
	double update_time_s = 0;                  ///< adding variables and measurements [s]
	double factor_time_s = 0;                  ///< reordering and (re)factorising [s]
	double recovery_time_s = 0;                ///< solving for the state, covariances and marginals [s]

	/// Every counter as (name, value), in the order above, prefixed with
	/// `prefix` (e.g. "sparse_"): ready for CostFigures::counters.
	std::vector<std::pair<std::string, double>> list(const std::string& prefix = "sparse_") const;

	/// Adds `part`'s counts and times (a retired core's, say); the sizes
	/// (information_nnz, factor_nnz) describe one core and are left alone,
	/// pcg_iterations_max takes the larger.
	SparseCounters& operator+=(const SparseCounters& part);
};

}  // namespace esif
