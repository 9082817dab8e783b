#include <esif/models/LocalMapObservation.h>

#include <cmath>

namespace esif
{
namespace
{
Eigen::Matrix2d rotation(double phi)
{
	const double c = std::cos(phi), s = std::sin(phi);
	Eigen::Matrix2d R;
	R << c, -s, s, c;
	return R;
}

/// d(R(phi)^T v) / d phi.
Eigen::Vector2d dRtDphi(double phi, const Eigen::Vector2d& v)
{
	const double c = std::cos(phi), s = std::sin(phi);
	return {-s * v.x() + c * v.y(), -c * v.x() - s * v.y()};
}
}  // namespace

PointInFrame pointInFrame(const Pose2& frame, const Eigen::Vector2d& point)
{
	const Eigen::Matrix2d Rt = rotation(frame.z()).transpose();
	const Eigen::Vector2d delta = point - frame.head<2>();
	PointInFrame out;
	out.value = Rt * delta;
	out.d_frame.leftCols<2>() = -Rt;
	out.d_frame.col(2) = dRtDphi(frame.z(), delta);
	out.d_point = Rt;
	return out;
}

PoseInFrame poseInFrame(const Pose2& frame, const Pose2& pose)
{
	const PointInFrame p = pointInFrame(frame, pose.head<2>());
	PoseInFrame out;
	out.value << p.value, wrapAngle(pose.z() - frame.z());
	out.d_frame.setZero();
	out.d_frame.topRows<2>() = p.d_frame;
	out.d_frame(2, 2) = -1;
	out.d_pose.setZero();
	out.d_pose.topLeftCorner<2, 2>() = p.d_point;
	out.d_pose(2, 2) = 1;
	return out;
}

PointFromFrame pointFromFrame(const Pose2& frame, const Eigen::Vector2d& local_point)
{
	const double c = std::cos(frame.z()), s = std::sin(frame.z());
	PointFromFrame out;
	out.d_point = rotation(frame.z());
	out.value = frame.head<2>() + out.d_point * local_point;
	out.d_frame << 1, 0, -s * local_point.x() - c * local_point.y(),  //
		0, 1, c * local_point.x() - s * local_point.y();
	return out;
}

LocalMapPrediction predictLocalMap(const Pose2& start, const Pose2& end, const std::vector<Eigen::Vector2d>& features)
{
	const Eigen::Index n = static_cast<Eigen::Index>(3 + 2 * features.size());
	LocalMapPrediction out;
	out.h.resize(n);
	out.d_start.resize(n, 3);
	out.d_state = Eigen::MatrixXd::Zero(n, n);
	const PoseInFrame e = poseInFrame(start, end);
	out.h.head<3>() = e.value;
	out.d_start.topRows<3>() = e.d_frame;
	out.d_state.topLeftCorner<3, 3>() = e.d_pose;
	for (std::size_t i = 0; i < features.size(); ++i)
	{
		const Eigen::Index r = static_cast<Eigen::Index>(3 + 2 * i);
		const PointInFrame p = pointInFrame(start, features[i]);
		out.h.segment<2>(r) = p.value;
		out.d_start.middleRows<2>(r) = p.d_frame;
		out.d_state.block<2, 2>(r, r) = p.d_point;
	}
	return out;
}

}  // namespace esif
