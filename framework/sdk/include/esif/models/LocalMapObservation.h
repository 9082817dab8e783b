#pragma once
/// \file LocalMapObservation.h
/// A local map seen as one "virtual observation" made from its start pose s
/// (book eq. 5.8): the end pose e and every feature p_i expressed in the
/// frame of s,
///     h(s, e, p_1..p_n) = [ R(phi_s)^T (e_xy - s_xy);  phi_e - phi_s;
///                           R(phi_s)^T (p_i - s_xy) ... ],
/// with its Jacobians. Also moves points and poses between a frame and its
/// parent, the operations of feature initialisation (eq. 5.7) and of the
/// association transform (eq. 5.11-5.12).

#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <vector>

namespace esif
{
/// A point of the parent frame expressed in the frame of a pose.
struct PointInFrame
{
	Eigen::Vector2d value;
	Eigen::Matrix<double, 2, 3> d_frame;  ///< d value / d(frame x, y, phi)
	Eigen::Matrix2d d_point;  ///< d value / d(point x, y) = R(phi)^T
};
PointInFrame pointInFrame(const Pose2& frame, const Eigen::Vector2d& point);

/// A pose of the parent frame expressed in the frame of another pose
/// (inverseCompose(frame, pose)), heading wrapped.
struct PoseInFrame
{
	Pose2 value;
	Eigen::Matrix3d d_frame;  ///< d value / d frame
	Eigen::Matrix3d d_pose;	 ///< d value / d pose
};
PoseInFrame poseInFrame(const Pose2& frame, const Pose2& pose);

/// A point given in the frame of `frame` expressed in the parent frame
/// (eq. 5.7, 5.11), with its Jacobians.
struct PointFromFrame
{
	Eigen::Vector2d value;
	Eigen::Matrix<double, 2, 3> d_frame;  ///< d value / d frame
	Eigen::Matrix2d d_point;  ///< d value / d local point = R(phi)
};
PointFromFrame pointFromFrame(const Pose2& frame, const Eigen::Vector2d& local_point);

/// Eq. (5.8) for one local map: h stacked as [end pose (3); features (2 each)]
/// and its Jacobian with respect to the start pose (rows x 3) and to
/// [end pose; features] (block diagonal: d_pose for the end pose, R^T for each feature).
struct LocalMapPrediction
{
	Eigen::VectorXd h;
	Eigen::MatrixXd d_start;
	Eigen::MatrixXd d_state;
};
LocalMapPrediction predictLocalMap(const Pose2& start, const Pose2& end, const std::vector<Eigen::Vector2d>& features);

}  // namespace esif
