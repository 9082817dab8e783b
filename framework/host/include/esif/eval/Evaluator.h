#pragma once
/// \file Evaluator.h
/// Accuracy and consistency against ground truth, in the frame of the initial
/// robot pose (relative SLAM, Sec. 1.3.1): no alignment is fitted, so an
/// error in the estimate is never hidden by a best-fit transform.

#include <esif/core/Estimate.h>
#include <esif/eval/EstimationErrors.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/RunRecord.h>

#include <map>
#include <optional>
#include <vector>

namespace esif
{
struct Accuracy
{
	std::optional<double> landmark_rmse_m;	///< RMS position error of matched landmarks
	std::optional<double> ate_rmse_m;  ///< RMS position error of the trajectory
	std::optional<double> landmark_nees_mean;  ///< mean NEES (2 dof) over landmarks
	std::optional<double> pose_nees_mean;  ///< mean NEES (3 dof) of the robot pose over steps
	/// Fraction of landmarks whose NEES is below the 95% chi-square bound (5.991).
	std::optional<double> landmark_consistent_fraction;
	/// Fraction of steps whose pose NEES is below the 95% bound (7.815).
	std::optional<double> pose_consistent_fraction;
	std::size_t landmarks_evaluated = 0;
	std::size_t poses_evaluated = 0;
};

/// `truth` must already be in the initial-pose frame. `filter_to_true` maps
/// each estimated landmark ID to a ground-truth ID (identity when the filter
/// used the rawlog's IDs); landmarks without a mapping are not scored.
/// Trajectory point k is compared with path row k for the steps both have.
/// The figures above from a run's error rows (EstimationErrors.h).
Accuracy summarizeErrors(const std::vector<PoseError>& poses, const std::vector<LandmarkError>& landmarks);

/// summarizeErrors() of poseErrors() and landmarkErrors().
Accuracy evaluate(
	const GroundTruth& truth, const std::vector<TrajectoryPoint>& trajectory, const Estimate& estimate,
	const std::map<LandmarkId, LandmarkId>& filter_to_true);

}  // namespace esif
