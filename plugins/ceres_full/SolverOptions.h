#pragma once
/// \file SolverOptions.h
/// Ceres solver options from [ceres_full]: sparse normal equations
/// factored by CHOLMOD, the trust-region strategy and damping chosen by the
/// user, and loose (intermediate) or full (final) stopping rules.

#include "CeresFullParams.h"

#include <ceres/ceres.h>

namespace esif::ceres_full
{
enum class SolveKind
{
	Intermediate,  ///< a re-solve during the run: only keeps the estimate in the basin
	Final  ///< the solve after the last step: to full tolerance
};

ceres::Solver::Options solverOptions(const CeresFullParams& params, SolveKind kind, int threads);

}  // namespace esif::ceres_full
