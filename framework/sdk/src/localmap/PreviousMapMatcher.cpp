#include <esif/association/PointSetAssociation.h>
#include "localmap/PreviousMapMatcher.h"
#include <esif/models/LocalMapObservation.h>

#include <stdexcept>

namespace esif
{
namespace
{
/// The open map's start pose in the previous map's frame, and its Jacobians
/// with respect to the previous end pose and the link odometry.
struct StartPose
{
	Pose2 value;
	Eigen::Matrix3d d_end = Eigen::Matrix3d::Identity();
	Eigen::Matrix3d d_link = Eigen::Matrix3d::Zero();
	Eigen::Matrix3d link_cov = Eigen::Matrix3d::Zero();
};

StartPose startPoseOf(const LocalMap& previous, const std::optional<OdometryIncrement>& link)
{
	StartPose s{previous.end_pose};
	if (!link) return s;
	const Pose2 u = link->delta;
	const auto J = composeJacobians(previous.end_pose, u);
	s.value = compose(previous.end_pose, u);
	s.d_end = J.d_a;
	s.d_link = J.d_b;
	s.link_cov = link->cov;
	return s;
}
}  // namespace

std::vector<std::optional<std::size_t>> matchPreviousMap(
	const LocalMap& previous, const std::optional<OdometryIncrement>& link, const OpenMapFeatures& open,
	AssociationMethod method, double gate_quantile)
{
	if (!previous.covariance)
		throw std::invalid_argument("matchPreviousMap: the previous local map has no covariance");
	const auto M = open.positions.rows();
	const auto N = static_cast<Eigen::Index>(previous.features.size());
	std::vector<std::optional<std::size_t>> out(M);
	if (M == 0 || N == 0) return out;

	// y = the previous features in the open map's frame; J = dy / d[end pose; features].
	const StartPose s = startPoseOf(previous, link);
	PointSets sets;
	sets.observed = open.positions;
	sets.observed_cov = open.covariance;
	sets.candidates.resize(N, 2);
	Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * N, previous.stateDim());
	Eigen::MatrixXd J_link(2 * N, 3);
	for (Eigen::Index c = 0; c < N; ++c)
	{
		const PointInFrame p = pointInFrame(s.value, previous.features[c].position);
		sets.candidates.row(c) = p.value.transpose();
		J.block<2, 3>(2 * c, 0) = p.d_frame * s.d_end;
		J.block<2, 2>(2 * c, 3 + 2 * c) = p.d_point;
		J_link.middleRows<2>(2 * c) = p.d_frame * s.d_link;
	}
	sets.candidates_cov = J * *previous.covariance * J.transpose() + J_link * s.link_cov * J_link.transpose();

	const auto result = associatePointSets(sets, method, gate_quantile, gate_quantile);
	for (Eigen::Index i = 0; i < M; ++i)
		if (result.candidate_of[i] >= 0) out[i] = static_cast<std::size_t>(result.candidate_of[i]);
	return out;
}

}  // namespace esif
