#include <esif/association/Chi2.h>
#include <esif/eval/Evaluator.h>

#include <cmath>

namespace esif
{
namespace
{
void scoreLandmarks(const std::vector<LandmarkError>& rows, Accuracy& acc)
{
	const double bound = chi2Quantile(0.95, 2);
	double sq = 0, nees_sum = 0;
	std::size_t n_nees = 0, consistent = 0;
	for (const auto& row : rows)
	{
		sq += row.error.squaredNorm();
		// A landmark whose covariance is not positive definite counts as inconsistent.
		if (row.nees)
		{
			nees_sum += *row.nees;
			++n_nees;
			if (*row.nees < bound) ++consistent;
		}
	}
	const std::size_t n = rows.size();
	acc.landmarks_evaluated = n;
	if (n == 0) return;
	acc.landmark_rmse_m = std::sqrt(sq / n);
	// No covariance at all (e.g. a full-SLAM run whose marginals could not be
	// computed): no consistency figure either, rather than a false 0.
	if (n_nees == 0) return;
	acc.landmark_consistent_fraction = static_cast<double>(consistent) / n;
	acc.landmark_nees_mean = nees_sum / n_nees;
}

void scoreTrajectory(const std::vector<PoseError>& rows, Accuracy& acc)
{
	const double bound = chi2Quantile(0.95, 3);
	double sq = 0, nees_sum = 0;
	std::size_t n_nees = 0, consistent = 0;
	for (const auto& row : rows)
	{
		sq += row.error.head<2>().squaredNorm();
		if (row.nees)
		{
			nees_sum += *row.nees;
			++n_nees;
			if (*row.nees < bound) ++consistent;
		}
	}
	const std::size_t n = rows.size();
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

Accuracy summarizeErrors(const std::vector<PoseError>& poses, const std::vector<LandmarkError>& landmarks)
{
	Accuracy acc;
	scoreLandmarks(landmarks, acc);
	scoreTrajectory(poses, acc);
	return acc;
}

Accuracy evaluate(
	const GroundTruth& truth, const std::vector<TrajectoryPoint>& trajectory, const Estimate& estimate,
	const std::map<LandmarkId, LandmarkId>& filter_to_true)
{
	return summarizeErrors(poseErrors(truth, trajectory), landmarkErrors(truth, estimate, filter_to_true));
}

}  // namespace esif
