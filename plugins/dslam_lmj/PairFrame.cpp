#include "PairFrame.h"

#include <esif/models/LocalMapObservation.h>

#include <cmath>

namespace esif::lmj
{
PairFrame pairFrame(const Eigen::Vector2d& f1, const Eigen::Vector2d& f2)
{
	const Eigen::Vector2d d = f2 - f1;
	const double d2 = d.squaredNorm();
	// d atan2(dy, dx) / d(dx, dy) = (-dy, dx) / |d|^2
	const Eigen::RowVector2d g(-d.y() / d2, d.x() / d2);
	PairFrame out;
	out.pose << f1, std::atan2(d.y(), d.x());
	out.d_pair.setZero();
	out.d_pair.block<2, 2>(0, 0).setIdentity();
	out.d_pair.block<1, 2>(2, 0) = -g;
	out.d_pair.block<1, 2>(2, 2) = g;
	return out;
}

PoseEstimate robotFromPairs(const Pose2& robot_local, const Eigen::Vector2d& f1_local, const Eigen::Vector2d& f2_local,
							const Eigen::MatrixXd& local_cov, const Eigen::Vector2d& f1_global,
							const Eigen::Vector2d& f2_global, const Eigen::Matrix4d& global_cov)
{
	// The robot in the pair's frame (from the local map), then out of the
	// pair's frame in the global map.
	const PairFrame local = pairFrame(f1_local, f2_local), global = pairFrame(f1_global, f2_global);
	const PoseInFrame in_pair = poseInFrame(local.pose, robot_local);
	const ComposeJacobians out = composeJacobians(global.pose, in_pair.value);
	Eigen::Matrix<double, 3, 7> A;	// d robot_global / d(robot_local, f1_local, f2_local)
	A.leftCols<3>() = out.d_b * in_pair.d_pose;
	A.rightCols<4>() = out.d_b * in_pair.d_frame * local.d_pair;
	const Eigen::Matrix<double, 3, 4> B = out.d_a * global.d_pair;	// d robot_global / d(f1_global, f2_global)
	Eigen::Matrix3d P = A * local_cov * A.transpose() + B * global_cov * B.transpose();
	return {compose(global.pose, in_pair.value), 0.5 * (P + P.transpose())};
}

std::vector<Eigen::Index> robotAndPairRows(int a, int b)
{
	return {0, 1, 2, 3 + 2 * a, 4 + 2 * a, 3 + 2 * b, 4 + 2 * b};
}

}  // namespace esif::lmj
