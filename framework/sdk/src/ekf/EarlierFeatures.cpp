#include <esif/ekf/EarlierFeatures.h>
#include <esif/models/LocalMapObservation.h>

#include <stdexcept>

namespace esif
{
EarlierFeatures earlierFeaturesInFrame(const Pose2& frame, const std::vector<LandmarkId>& ids,
									   const std::vector<Eigen::Vector2d>& points, const Eigen::MatrixXd& joint_cov)
{
	const auto n = static_cast<Eigen::Index>(points.size());
	if (ids.size() != points.size() || joint_cov.rows() != 3 + 2 * n || joint_cov.cols() != 3 + 2 * n)
		throw std::invalid_argument("earlierFeaturesInFrame: sizes of ids, points and covariance differ");
	EarlierFeatures out;
	out.ids = ids;
	out.positions.resize(2 * n);
	Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * n, 3 + 2 * n);
	for (Eigen::Index i = 0; i < n; ++i)
	{
		const PointInFrame y = pointInFrame(frame, points[static_cast<std::size_t>(i)]);
		out.positions.segment<2>(2 * i) = y.value;
		J.block<2, 3>(2 * i, 0) = y.d_frame;
		J.block<2, 2>(2 * i, 3 + 2 * i) = y.d_point;
	}
	out.covariance = J * joint_cov * J.transpose();
	out.covariance = (0.5 * (out.covariance + out.covariance.transpose())).eval();
	return out;
}

EarlierFeatures EarlierFeatures::inFrame(const Pose2& frame, const Eigen::Matrix3d& frame_cov) const
{
	const auto n = static_cast<Eigen::Index>(size());
	Eigen::MatrixXd joint = Eigen::MatrixXd::Zero(3 + 2 * n, 3 + 2 * n);
	joint.topLeftCorner<3, 3>() = frame_cov;
	joint.bottomRightCorner(2 * n, 2 * n) = covariance;
	std::vector<Eigen::Vector2d> points;
	for (std::size_t i = 0; i < size(); ++i) points.push_back(position(i));
	return earlierFeaturesInFrame(frame, ids, points, joint);
}

}  // namespace esif
