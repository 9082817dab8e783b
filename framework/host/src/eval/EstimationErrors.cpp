#include <esif/eval/EstimationErrors.h>
#include <esif/models/Se2.h>

#include <Eigen/Cholesky>

namespace esif
{
std::optional<double> nees(const Eigen::VectorXd& error, const Eigen::MatrixXd& cov)
{
	const Eigen::LLT<Eigen::MatrixXd> llt(cov);
	if (llt.info() != Eigen::Success) return std::nullopt;
	return error.dot(llt.solve(error));
}

std::vector<PoseError> poseErrors(const GroundTruth& truth, const std::vector<TrajectoryPoint>& trajectory)
{
	std::vector<PoseError> rows;
	rows.reserve(trajectory.size());
	for (const auto& tp : trajectory)
	{
		if (tp.step >= truth.path.size()) continue;
		PoseError row;
		row.step = tp.step;
		row.error = tp.pose.mean - truth.path[tp.step];
		row.error(2) = wrapAngle(row.error(2));
		// The initial pose is known exactly: no NEES there, whether its
		// covariance is zero or the tiny floor of a first zero move (1e-10:
		// its NEES of a zero error would be a meaningless 0, below any bound).
		if (tp.step > 0 && tp.pose.cov.trace() > 0) row.nees = nees(row.error, tp.pose.cov);
		if (row.nees)
		{
			row.position_nees = nees(row.error.head<2>(), tp.pose.cov.topLeftCorner<2, 2>());
			row.heading_nees = nees(row.error.tail<1>(), tp.pose.cov.bottomRightCorner<1, 1>());
		}
		rows.push_back(row);
	}
	return rows;
}

std::vector<LandmarkError> landmarkErrors(
	const GroundTruth& truth, const Estimate& estimate, const std::map<LandmarkId, LandmarkId>& filter_to_true)
{
	std::vector<LandmarkError> rows;
	for (const auto& lm : estimate.landmarks)
	{
		const auto map_it = filter_to_true.find(lm.id);
		if (map_it == filter_to_true.end()) continue;
		const auto gt_it = truth.landmarks.find(map_it->second);
		if (gt_it == truth.landmarks.end()) continue;
		LandmarkError row;
		row.true_id = map_it->second;
		row.error = lm.mean - gt_it->second;
		row.nees = nees(row.error, lm.cov);
		rows.push_back(row);
	}
	return rows;
}

}  // namespace esif
