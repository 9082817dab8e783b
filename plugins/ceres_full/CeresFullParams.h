#pragma once
/// \file CeresFullParams.h
/// Parameters of the full-SLAM optimization baseline, INI section [ceres_full].

#include <esif/config/ParamBinder.h>

#include <string>

namespace esif::ceres_full
{
enum class RobustLoss
{
	None,  ///< plain least squares: the MAP estimate of eq. 1.21
	Huber,
	Cauchy
};

/// Which marginal covariances finish() computes.
enum class CovarianceScope
{
	None,  ///< none (fastest; NEES and ellipses are then unavailable)
	LandmarksAndFinalPose,	///< every landmark and the last pose, as the filters report
	AllPoses  ///< also every pose of the trajectory (pose NEES over all steps)
};

struct CeresFullParams
{
	/// 0: one batch solve at the end of the rawlog; K > 0: also re-solve after
	/// every K steps, so the running trajectory is the optimum so far.
	int resolve_every_steps = 0;
	int max_iterations = 200;  ///< Levenberg-Marquardt iterations per solve
	double function_tolerance = 1e-10;	///< relative cost change that ends a solve
	double gradient_tolerance = 1e-12;
	double parameter_tolerance = 1e-10;
	int threads = 0;  ///< Jacobian evaluation and covariance threads; 0 = every core
	RobustLoss robust_loss = RobustLoss::None;	///< on range-bearing terms only
	double robust_loss_scale = 3.0;	 ///< whitened residual norm where the loss turns robust [sigma]
	CovarianceScope covariance = CovarianceScope::LandmarksAndFinalPose;
	/// Run folder (trajectory.tum, landmarks.txt) whose estimate is the initial
	/// guess; empty = dead reckoning and first sightings.
	std::string initial_run;

	void declare(ParamBinder& b);
};

}  // namespace esif::ceres_full
