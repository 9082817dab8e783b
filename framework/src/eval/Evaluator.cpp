#include <esif/association/Chi2.h>
#include <esif/eval/Evaluator.h>
#include <esif/models/Se2.h>

#include <Eigen/Cholesky>
#include <cmath>

namespace esif
{
std::optional<double> nees(const Eigen::VectorXd& error, const Eigen::MatrixXd& cov)
{
	const Eigen::LLT<Eigen::MatrixXd> llt(cov);
	if (llt.info() != Eigen::Success) return std::nullopt;
	return error.dot(llt.solve(error));
}

namespace
{
void scoreLandmarks(
	const GroundTruth& truth, const Estimate& estimate, const std::map<LandmarkId, LandmarkId>& filter_to_true,
	Accuracy& acc)
{
	const double bound = chi2Quantile(0.95, 2);
	double sq = 0, nees_sum = 0;
	std::size_t n = 0, n_nees = 0, consistent = 0;
	for (const auto& lm : estimate.landmarks)
	{
		const auto map_it = filter_to_true.find(lm.id);
		if (map_it == filter_to_true.end()) continue;
		const auto gt_it = truth.landmarks.find(map_it->second);
		if (gt_it == truth.landmarks.end()) continue;
		const Eigen::Vector2d e = lm.mean - gt_it->second;
		sq += e.squaredNorm();
		++n;
		// A landmark whose covariance is not positive definite counts as inconsistent.
		if (const auto v = nees(e, lm.cov))
		{
			nees_sum += *v;
			++n_nees;
			if (*v < bound) ++consistent;
		}
	}
	acc.landmarks_evaluated = n;
	if (n == 0) return;
	acc.landmark_rmse_m = std::sqrt(sq / n);
	// No covariance at all (e.g. a full-SLAM run whose marginals could not be
	// computed): no consistency figure either, rather than a false 0.
	if (n_nees == 0) return;
	acc.landmark_consistent_fraction = static_cast<double>(consistent) / n;
	acc.landmark_nees_mean = nees_sum / n_nees;
}

void scoreTrajectory(const GroundTruth& truth, const std::vector<TrajectoryPoint>& trajectory, Accuracy& acc)
{
	const double bound = chi2Quantile(0.95, 3);
	double sq = 0, nees_sum = 0;
	std::size_t n = 0, n_nees = 0, consistent = 0;
	for (const auto& tp : trajectory)
	{
		if (tp.step >= truth.path.size()) continue;
		const Pose2& gt = truth.path[tp.step];
		Eigen::Vector3d e = toPose2(tp.pose.mean) - gt;
		e(2) = wrapAngle(e(2));
		sq += e.head<2>().squaredNorm();
		++n;
		// The initial pose is known exactly (zero covariance): no NEES there.
		if (tp.pose.cov.trace() <= 0) continue;
		if (const auto v = nees(e, tp.pose.cov))
		{
			nees_sum += *v;
			++n_nees;
			if (*v < bound) ++consistent;
		}
	}
	acc.poses_evaluated = n;
	if (n == 0) return;
	acc.ate_rmse_m = std::sqrt(sq / n);
	if (n_nees > 0)
	{
		acc.pose_nees_mean = nees_sum / n_nees;
		acc.pose_consistent_fraction = static_cast<double>(consistent) / n_nees;
	}
}
}  // namespace

Accuracy evaluate(
	const GroundTruth& truth, const std::vector<TrajectoryPoint>& trajectory, const Estimate& estimate,
	const std::map<LandmarkId, LandmarkId>& filter_to_true)
{
	Accuracy acc;
	scoreLandmarks(truth, estimate, filter_to_true, acc);
	scoreTrajectory(truth, trajectory, acc);
	return acc;
}

}  // namespace esif
