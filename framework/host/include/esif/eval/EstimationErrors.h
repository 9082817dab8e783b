#pragma once
/// \file EstimationErrors.h
/// The errors of one run against ground truth, one row per step and per
/// landmark, in the frame of the initial robot pose (no alignment). The
/// run's accuracy figures (Evaluator.h) are summaries of these rows; a Monte
/// Carlo campaign averages them over runs (MonteCarloStatistics.h).

#include <esif/core/Estimate.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/RunRecord.h>

#include <Eigen/Core>
#include <map>
#include <optional>
#include <vector>

namespace esif
{
/// The filtered robot pose of one step minus the true pose.
struct PoseError
{
	std::size_t step = 0;
	Eigen::Vector3d error = Eigen::Vector3d::Zero();  ///< (x [m], y [m], heading [rad] wrapped to (-pi, pi])
	/// e^T P^-1 e (3 dof); none at the initial pose (step 0, known exactly),
	/// with a zero covariance, or when P is not positive definite.
	std::optional<double> nees;
	/// The same split by the pose's marginals, to tell which part of the pose
	/// is over- or under-confident: position (2 dof, the x-y block of P) and
	/// heading (1 dof, e_theta^2 / P_theta_theta); none where `nees` is none.
	std::optional<double> position_nees;
	std::optional<double> heading_nees;
};

/// A landmark of the final map minus its true position.
struct LandmarkError
{
	LandmarkId true_id = 0;	 ///< the ground-truth landmark it is paired with
	Eigen::Vector2d error = Eigen::Vector2d::Zero();  ///< [m]
	std::optional<double> nees;	 ///< 2 dof; none when the covariance is not positive definite
};

/// NEES e^T P^-1 e; nullopt when P is not positive definite.
std::optional<double> nees(const Eigen::VectorXd& error, const Eigen::MatrixXd& cov);

/// One row per trajectory point whose step the ground-truth path has.
/// `truth` must be in the initial-pose frame.
std::vector<PoseError> poseErrors(const GroundTruth& truth, const std::vector<TrajectoryPoint>& trajectory);

/// One row per landmark of `estimate` that `filter_to_true` maps to a
/// ground-truth landmark, in the estimate's order.
std::vector<LandmarkError> landmarkErrors(
	const GroundTruth& truth, const Estimate& estimate, const std::map<LandmarkId, LandmarkId>& filter_to_true);

}  // namespace esif
