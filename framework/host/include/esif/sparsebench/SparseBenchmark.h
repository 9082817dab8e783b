#pragma once
/// \file SparseBenchmark.h
/// Timing of the recovery methods on a D-SLAM-like sequence (`esif bench
/// sparse`): the robot first maps every feature (rows sweep, not timed, no
/// recovery), then goes on sweeping (columns, revisiting and closing loops)
/// for the timed steps, each step adding its measurement and recovering the
/// whole state, as a D-SLAM mapper would.

#include <esif/sparse/SparseRecoveryParams.h>

#include <cstddef>
#include <string>
#include <vector>

namespace esif
{
struct SparseBenchResult
{
	std::string method;
	int features = 0;
	int steps = 0;                             ///< timed steps
	double us_per_step = 0;                    ///< mean wall time of update + state recovery [us]
	std::size_t factor_nnz = 0;                ///< at the end (dense: n(n+1)/2)
	std::size_t reorders = 0;                  ///< fresh (re)orderings during the timed steps
	std::size_t partial_refactorisations = 0;  ///< during the timed steps
	double pcg_iterations_mean = 0;            ///< per state solve, timed steps
	std::size_t pcg_iterations_max = 0;
	double update_s = 0;    ///< timed steps: adding the measurements [s]
	double factor_s = 0;    ///< timed steps: reordering and (re)factorising [s]
	double recovery_s = 0;  ///< timed steps: solving for the state [s]
	double total_s = 0;     ///< whole run including the mapping sweep [s]
};

/// The methods runSparseBenchmark knows: incremental_cholesky (book
/// ordering), incremental_cholesky_camd, pcg, pcg_camd, fresh_cholesky,
/// dense_inverse.
const std::vector<std::string>& sparseBenchMethods();

/// Runs `method` on a sequence over `features` features for `steps` timed
/// steps. `base` supplies n0 and the tolerances; recovery and reordering
/// follow from the method name. Throws ConfigError for an unknown method.
SparseBenchResult runSparseBenchmark(const std::string& method, int features, int steps,
									 const SparseRecoveryParams& base, unsigned seed = 1);

}  // namespace esif
