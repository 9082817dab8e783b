#pragma once
/// \file PairFrame.h
/// The frame of two features f1, f2: origin at f1, x axis along f1 -> f2.
/// It is the frame of the book's star form (eq. 4.7): a feature's
/// coordinates in it are a one-to-one function of its (d_1i, alpha_i12),
/// and the same in any frame the two features are expressed in. So a local
/// map and the global map, each moved into the frame of the same two
/// features, can be compared without knowing where the local map lies
/// (upper-level association, Sec. 4.4.2), and the robot's pose in that
/// frame carries it into the global map (Sec. 4.4.1).

#include <esif/core/Estimate.h>
#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <vector>

namespace esif::lmj
{
/// The pair's frame as a pose, with its Jacobian with respect to
/// (f1x, f1y, f2x, f2y).
struct PairFrame
{
	Pose2 pose;
	Eigen::Matrix<double, 3, 4> d_pair;
};
PairFrame pairFrame(const Eigen::Vector2d& f1, const Eigen::Vector2d& f2);

/// Eq. 4.4.1: the robot pose in the global map from the pair in both maps.
/// `local` = (robot pose, f1, f2) in the local map with their joint 7x7
/// covariance; `global_f1f2` = (f1, f2) in the global map with their joint
/// 4x4 covariance; the two estimates are independent until the local map is
/// fused. First-order covariance.
PoseEstimate robotFromPairs(const Pose2& robot_local, const Eigen::Vector2d& f1_local, const Eigen::Vector2d& f2_local,
							const Eigen::MatrixXd& local_cov, const Eigen::Vector2d& f1_global,
							const Eigen::Vector2d& f2_global, const Eigen::Matrix4d& global_cov);

/// Rows of a local state [robot; features] for the robot and features a, b:
/// the local_cov of robotFromPairs is the covariance at these rows.
std::vector<Eigen::Index> robotAndPairRows(int a, int b);

}  // namespace esif::lmj
