#pragma once
/// \file CeresFullParams.h
/// Parameters of the full-SLAM optimization baseline, INI section [ceres_full].

#include <esif/config/ParamBinder.h>

#include <string>

namespace esif::ceres_full
{
enum class RobustLoss
{
	None = 0,  ///< plain least squares: the MAP estimate of eq. 1.21
	Huber = 1,
	Cauchy = 2
};

/// Which marginal covariances finish() computes.
enum class CovarianceScope
{
	None,  ///< none (fastest; NEES and ellipses are then unavailable)
	LandmarksAndFinalPose,	///< every landmark and the last pose, as the filters report
	AllPoses  ///< also every pose of the trajectory (pose NEES over all steps)
};

/// What the final solve does with measurements the model cannot explain.
enum class OutlierPolicy
{
	Keep,  ///< every measurement is a term of eq. 1.21
	Drop   ///< converge with a robust loss, drop those failing the gate, solve eq. 1.21 on the rest
};

/// Ceres' trust-region step: Levenberg-Marquardt or Powell's dogleg.
enum class TrustRegion
{
	LevenbergMarquardt,
	Dogleg
};

struct CeresFullParams
{
	// When to solve. Between solves every new pose starts from odometry
	// composed onto the current estimate (the optimum of the last solve and
	// dead reckoning since), every new landmark from its first measurement.
	/// Re-solve once the pose count has grown by this fraction since the
	/// last solve (0 = never): solve sizes grow geometrically, so the work
	/// of all intermediate solves is (1 + 1/g) times that of one full solve.
	double resolve_growth = 0.2;
	/// ... but never after fewer new poses than this.
	int resolve_min_new_poses = 20;
	/// Refine each new pose by the step's measurements of mapped landmarks
	/// (PoseRefiner) before its new landmarks are placed.
	bool refine_new_poses = true;
	/// Also re-solve after every K steps (0 = off); the older, quadratic schedule.
	int resolve_every_steps = 0;
	/// Intermediate solves only need to keep the estimate in the basin of the
	/// optimum: few iterations and a loose tolerance.
	int intermediate_max_iterations = 50;
	double intermediate_function_tolerance = 1e-6;
	double intermediate_parameter_tolerance = 1e-6;

	// The final solve.
	int max_iterations = 200;  ///< trust-region iterations of the final solve
	double function_tolerance = 1e-10;	///< relative cost change that ends a solve
	double gradient_tolerance = 1e-12;
	double parameter_tolerance = 1e-10;

	// Trust-region damping (Ceres' Solver::Options of the same names).
	/// Powell's dogleg: Levenberg-Marquardt stalls on the book's near rank-2
	/// velocity-model odometry (docs/plugins/ceres_full.md, "Damping").
	TrustRegion trust_region_strategy = TrustRegion::Dogleg;
	/// Ceres' Levenberg-Marquardt damps with mu D, D = diag(J^T J) clamped to
	/// [min_lm_diagonal, max_lm_diagonal], of J scaled to unit columns when
	/// jacobi_scaling is on (the dogleg regularises its Gauss-Newton step with
	/// the same D). Off with both clamps at 1: plain damping mu I, which
	/// converges where the diagonal-scaled damping crawls
	/// (docs/plugins/ceres_full.md, "Damping").
	bool jacobi_scaling = false;
	double initial_trust_region_radius = 1e4;
	double max_trust_region_radius = 1e16;
	double min_lm_diagonal = 1;
	double max_lm_diagonal = 1;

	/// Outliers (a misread ID, a reflection) are not Gaussian noise: one of
	/// them metres off drags the least-squares optimum by metres
	/// (docs/plugins/ceres_full.md, "Outliers"). With Drop every solve of the
	/// run uses a Huber loss (robust_loss_scale); the final one, converged
	/// so, drops every measurement whose whitened residual fails the gate and
	/// solves eq. 1.21 (or robust_loss) on the rest, repeating until no more
	/// is dropped: the result is the optimum of the measurements it keeps.
	OutlierPolicy outliers = OutlierPolicy::Drop;
	/// The gate's chance of dropping any inlier over the whole run: the
	/// chi-square(2) quantile 1 - rate / N of the N measurements (Bonferroni),
	/// so a clean log keeps every measurement (expected 0.01 drops) however
	/// long it is; 5.1 sigma for 4,000 measurements, 6.0 for 470,000.
	double outlier_false_drop_rate = 0.01;
	/// More measurements than this share beyond the gate is not a few
	/// outliers but a wrong solution (a collapsed pose, a wrong noise model):
	/// then nothing is dropped, the plain solve stands and is reported
	/// implausible. Well above real data's share (docs/plugins/ceres_full.md,
	/// "Outliers").
	double max_outlier_share = 0.02;

	int threads = 0;  ///< Jacobian evaluation and covariance threads; 0 = every core
	RobustLoss robust_loss = RobustLoss::None;	///< on range-bearing terms only
	double robust_loss_scale = 3.0;	 ///< whitened residual norm where the loss turns robust [sigma]
	CovarianceScope covariance = CovarianceScope::LandmarksAndFinalPose;

	// Checks of the final solution.
	/// A pose closer than this to a landmark it measured more than 5 range
	/// sigmas further away is degenerate (a collapsed solution) [m].
	double degenerate_distance_m = 0.05;
	/// chi2 / dof above this marks the optimum implausible (a local minimum
	/// or a wrong noise model or association).
	double max_chi2_per_dof = 3.0;

	void declare(ParamBinder& b);
};

}  // namespace esif::ceres_full
