#pragma once
/// \file PoseRefiner.h
/// The warm start of a new pose: its odometry composed onto the previous
/// pose's estimate, then refined by the step's measurements of landmarks
/// already mapped. Only the new pose is estimated (the previous pose and the
/// landmarks are held at their current values), so it costs a few
/// Gauss-Newton steps on three unknowns per step, yet it keeps the poses
/// between two re-solves as close to the map as the measurements allow
/// instead of drifting with dead reckoning (grid1225_large with re-solves at
/// 10 % growth but no refinement ends at chi2 9.0e8 for 155,190 dof).

#include <esif/core/StepInput.h>
#include <esif/models/Se2.h>

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <vector>

namespace esif::ceres_full
{
/// A measurement of a landmark whose position is already estimated.
struct MappedMeasurement
{
	Eigen::Vector2d landmark;
	RangeBearing measurement;
	Pose2 sensor_on_robot = Pose2::Zero();
};

/// The pose minimising the odometry term from `previous` and the range-bearing
/// terms of `seen` (book eq. 1.21 restricted to one pose), started at
/// `initial`. Returns `initial` when nothing is seen or the solve fails.
/// `loss` (may be null, not owned) is applied to the range-bearing terms.
Pose2 refineNewPose(
	const Pose2& previous, const OdometryIncrement& odometry, const Pose2& initial,
	const std::vector<MappedMeasurement>& seen, const ceres::LossFunction* loss);

}  // namespace esif::ceres_full
