#include "CeresFullParams.h"

namespace esif::ceres_full
{
namespace
{
void declareSchedule(CeresFullParams& p, ParamBinder& b)
{
	b.real("resolve_growth", p.resolve_growth,
		   "re-solve when the pose count has grown by this fraction since the last solve (0 = never); work grows "
		   "about linearly with the run",
		   Bounds::nonNegative());
	b.integer("resolve_min_new_poses", p.resolve_min_new_poses,
			  "fewest new poses between two re-solves of the growth schedule", Bounds::atLeast(1));
	b.flag("refine_new_poses", p.refine_new_poses,
		   "start each new pose from odometry refined by its measurements of landmarks already mapped (false = "
		   "odometry only)");
	b.integer("resolve_every_steps", p.resolve_every_steps, "also re-solve after every K steps (0 = off)",
			  Bounds::atLeast(0));
	b.integer("intermediate_max_iterations", p.intermediate_max_iterations,
			  "trust-region iterations of each re-solve during the run", Bounds::atLeast(1));
	b.real("intermediate_function_tolerance", p.intermediate_function_tolerance,
		   "relative cost decrease that ends a re-solve during the run", Bounds::positive());
	b.real("intermediate_parameter_tolerance", p.intermediate_parameter_tolerance,
		   "relative step size that ends a re-solve during the run", Bounds::positive());
}

void declareFinalSolve(CeresFullParams& p, ParamBinder& b)
{
	b.integer("max_iterations", p.max_iterations, "trust-region iterations of the final solve", Bounds::atLeast(1));
	b.real("function_tolerance", p.function_tolerance, "relative cost decrease below which the final solve has converged",
		   Bounds::positive());
	b.real("gradient_tolerance", p.gradient_tolerance, "max-norm of the scaled gradient that ends a solve",
		   Bounds::positive());
	b.real("parameter_tolerance", p.parameter_tolerance, "relative step size that ends a solve", Bounds::positive());
}

void declareTrustRegion(CeresFullParams& p, ParamBinder& b)
{
	b.enumeration<TrustRegion>(
		"trust_region_strategy", p.trust_region_strategy,
		{{"levenberg_marquardt", TrustRegion::LevenbergMarquardt}, {"dogleg", TrustRegion::Dogleg}},
		"trust-region step: levenberg_marquardt or dogleg (Powell's)");
	b.flag("jacobi_scaling", p.jacobi_scaling,
		   "scale J's columns to unit norm before the trust-region step (Ceres' default: on); off with "
		   "min_lm_diagonal = max_lm_diagonal = 1 gives plain damping mu I");
	b.real("initial_trust_region_radius", p.initial_trust_region_radius,
		   "first trust-region radius (Levenberg-Marquardt: 1 / initial damping)", Bounds::positive());
	b.real("max_trust_region_radius", p.max_trust_region_radius, "largest trust-region radius", Bounds::positive());
	b.real("min_lm_diagonal", p.min_lm_diagonal, "lower clamp of the Levenberg-Marquardt diagonal", Bounds::positive());
	b.real("max_lm_diagonal", p.max_lm_diagonal, "upper clamp of the Levenberg-Marquardt diagonal", Bounds::positive());
}

void declareModelAndOutputs(CeresFullParams& p, ParamBinder& b)
{
	b.integer("threads", p.threads, "threads for Jacobians and covariances (0 = every core)", Bounds::atLeast(0));
	b.enumeration<RobustLoss>(
		"robust_loss", p.robust_loss,
		{{"none", RobustLoss::None}, {"huber", RobustLoss::Huber}, {"cauchy", RobustLoss::Cauchy}},
		"loss on the range-bearing terms: none (the MAP estimate of eq. 1.21), huber or cauchy");
	b.real("robust_loss_scale", p.robust_loss_scale,
		   "whitened residual norm [sigma] beyond which the robust loss down-weights a measurement", Bounds::positive());
	b.enumeration<OutlierPolicy>(
		"outliers", p.outliers, {{"keep", OutlierPolicy::Keep}, {"drop", OutlierPolicy::Drop}},
		"keep: every measurement is a term of eq. 1.21; drop: converge with a Huber loss, drop the measurements "
		"failing the outlier gate, and solve eq. 1.21 on the rest");
	b.real("outlier_false_drop_rate", p.outlier_false_drop_rate,
		   "chance that the outlier gate drops any inlier over the whole run (gate: the chi-square(2) quantile 1 - "
		   "rate / measurements)",
		   Bounds::openUnit());
	b.real("max_outlier_share", p.max_outlier_share,
		   "largest share of measurements the outlier gate may drop; beyond it the solution, not the measurements, "
		   "is taken to be wrong: nothing is dropped and the optimum is reported implausible",
		   Bounds::openUnit());
	b.enumeration<CovarianceScope>(
		"covariance", p.covariance,
		{{"none", CovarianceScope::None},
		 {"landmarks_and_final_pose", CovarianceScope::LandmarksAndFinalPose},
		 {"all_poses", CovarianceScope::AllPoses}},
		"marginal covariances computed after the final solve (none disables NEES and ellipses)");
}

void declareChecks(CeresFullParams& p, ParamBinder& b)
{
	b.real("degenerate_distance_m", p.degenerate_distance_m,
		   "a pose this close to a landmark it measured more than 5 range sigmas further away is degenerate [m]",
		   Bounds::positive());
	b.real("max_chi2_per_dof", p.max_chi2_per_dof, "chi2 / dof above which the optimum is reported implausible",
		   Bounds::positive());
}
}  // namespace

void CeresFullParams::declare(ParamBinder& b)
{
	declareSchedule(*this, b);
	declareFinalSolve(*this, b);
	declareTrustRegion(*this, b);
	declareModelAndOutputs(*this, b);
	declareChecks(*this, b);
}

}  // namespace esif::ceres_full
