#pragma once
/// \file Se2.h
/// Planar rigid-body poses (x, y, phi) as Eigen vectors, with the composition
/// Jacobians used by every filter (book eq. 1.1, 1.8).

#include <esif/core/Estimate.h>

#include <mrpt/math/TPose2D.h>

#include <Eigen/Core>

namespace esif
{
/// Wraps an angle to (-pi, pi].
double wrapAngle(double a);

Pose2 toPose2(const mrpt::math::TPose2D& p);
mrpt::math::TPose2D toTPose2D(const Pose2& p);

/// a (+) b: pose b given in the frame of a, expressed in a's parent frame.
Pose2 compose(const Pose2& a, const Pose2& b);

/// a (-) b... written as inverseCompose(a, b) = b expressed in the frame of a (a^-1 (+) b).
Pose2 inverseCompose(const Pose2& a, const Pose2& b);

/// Jacobians of compose(a, b) with respect to a and to b.
struct ComposeJacobians
{
	Eigen::Matrix3d d_a;
	Eigen::Matrix3d d_b;
};
ComposeJacobians composeJacobians(const Pose2& a, const Pose2& b);

/// x (+) r for two independent estimates, with the first-order covariance
/// J_x P_x J_x^T + J_r P_r J_r^T (symmetrised): a local map's end pose
/// carried into another frame, a link appended to a chain of poses.
PoseEstimate composeIndependent(const PoseEstimate& x, const PoseEstimate& r);

/// Point p given in the frame of `pose`, expressed in the parent frame.
Eigen::Vector2d transformPoint(const Pose2& pose, const Eigen::Vector2d& p);

}  // namespace esif
