#include "CeresFullParams.h"

namespace esif::ceres_full
{
void CeresFullParams::declare(ParamBinder& b)
{
	b.integer("resolve_every_steps", resolve_every_steps,
			  "also re-solve after every K steps (0 = one batch solve at the end)", Bounds::atLeast(0));
	b.integer("max_iterations", max_iterations, "Levenberg-Marquardt iterations per solve", Bounds::atLeast(1));
	b.real("function_tolerance", function_tolerance, "relative cost decrease below which a solve has converged",
		   Bounds::positive());
	b.real("gradient_tolerance", gradient_tolerance, "max-norm of the scaled gradient that ends a solve",
		   Bounds::positive());
	b.real("parameter_tolerance", parameter_tolerance, "relative step size that ends a solve", Bounds::positive());
	b.integer("threads", threads, "threads for Jacobians and covariances (0 = every core)", Bounds::atLeast(0));
	b.enumeration<RobustLoss>(
		"robust_loss", robust_loss, {{"none", RobustLoss::None}, {"huber", RobustLoss::Huber}, {"cauchy", RobustLoss::Cauchy}},
		"loss on the range-bearing terms: none (the MAP estimate of eq. 1.21), huber or cauchy");
	b.real("robust_loss_scale", robust_loss_scale,
		   "whitened residual norm [sigma] beyond which the robust loss down-weights a measurement", Bounds::positive());
	b.enumeration<CovarianceScope>(
		"covariance", covariance,
		{{"none", CovarianceScope::None},
		 {"landmarks_and_final_pose", CovarianceScope::LandmarksAndFinalPose},
		 {"all_poses", CovarianceScope::AllPoses}},
		"marginal covariances computed after the final solve (none disables NEES and ellipses)");
	b.text("initial_run", initial_run,
		   "run folder whose trajectory.tum and landmarks.txt are the initial guess (empty = dead reckoning and "
		   "first sightings)");
}

}  // namespace esif::ceres_full
