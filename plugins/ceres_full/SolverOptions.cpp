#include "SolverOptions.h"

namespace esif::ceres_full
{
namespace
{
void setDamping(const CeresFullParams& p, ceres::Solver::Options& o)
{
	o.trust_region_strategy_type =
		p.trust_region_strategy == TrustRegion::Dogleg ? ceres::DOGLEG : ceres::LEVENBERG_MARQUARDT;
	// Ceres' Levenberg-Marquardt damps with mu diag(J^T J) (Marquardt's
	// scaling), clamped to [min_lm_diagonal, max_lm_diagonal]; with unit
	// clamps and no Jacobi scaling that is plain mu I (see CeresFullParams.h).
	o.jacobi_scaling = p.jacobi_scaling;
	o.initial_trust_region_radius = p.initial_trust_region_radius;
	o.max_trust_region_radius = p.max_trust_region_radius;	// >= the initial radius (validated)
	o.min_lm_diagonal = p.min_lm_diagonal;
	o.max_lm_diagonal = p.max_lm_diagonal;  // >= min_lm_diagonal (validated)
}
}  // namespace

ceres::Solver::Options solverOptions(const CeresFullParams& p, SolveKind kind, int threads)
{
	ceres::Solver::Options o;
	o.minimizer_type = ceres::TRUST_REGION;
	o.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
	o.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
	setDamping(p, o);
	o.gradient_tolerance = p.gradient_tolerance;
	if (kind == SolveKind::Final)
	{
		o.max_num_iterations = p.max_iterations;
		o.function_tolerance = p.function_tolerance;
		o.parameter_tolerance = p.parameter_tolerance;
	}
	else
	{
		o.max_num_iterations = p.intermediate_max_iterations;
		o.function_tolerance = p.intermediate_function_tolerance;
		o.parameter_tolerance = p.intermediate_parameter_tolerance;
	}
	o.num_threads = threads;
	o.logging_type = ceres::SILENT;
	return o;
}

}  // namespace esif::ceres_full
