#include "OutlierGate.h"

#include <esif/association/Chi2.h>
#include <esif/models/RangeBearingModel.h>

#include <Eigen/Cholesky>
#include <limits>

namespace esif::dslam
{
std::vector<int> localOutliers(const LocalSlam& local, const std::vector<IdentifiedMeasurement>& scan,
							   const Pose2& sensor_on_robot, double quantile)
{
	const double gate = chi2Quantile(quantile, 2);
	std::vector<int> out;
	for (std::size_t i = 0; i < scan.size(); ++i)
	{
		const auto d2 = local.innovationDistance2(scan[i], sensor_on_robot);
		if (d2 && *d2 > gate) out.push_back(static_cast<int>(i));
	}
	return out;
}

double reobservationDistance2(const Pose2& robot, const Eigen::Matrix3d& robot_cov, const Pose2& sensor_on_robot,
							  const Eigen::Vector2d& feature, const Eigen::Matrix2d& feature_cov,
							  const IdentifiedMeasurement& m)
{
	const RangeBearingPrediction h = predictRangeBearing(robot, sensor_on_robot, feature);
	Eigen::Vector2d nu = m.z - h.z;
	nu(1) = wrapAngle(nu(1));
	Eigen::Matrix2d S = h.d_robot * robot_cov * h.d_robot.transpose() +
		h.d_landmark * feature_cov * h.d_landmark.transpose() + m.R;
	S = 0.5 * (S + S.transpose()).eval();
	const Eigen::LDLT<Eigen::Matrix2d> ldlt(S);
	if (ldlt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
	return nu.dot(ldlt.solve(nu));
}

std::pair<double, int> relativeDistance2(const MappedView& view, const std::vector<int>& keep)
{
	std::vector<Eigen::Index> rows;
	for (int i : keep)
	{
		rows.push_back(2 * i);
		rows.push_back(2 * i + 1);
	}
	const relative::ValueJacobian z = relative::relativeGeometry(view.measured.xy(rows));
	const relative::ValueJacobian h = relative::relativeGeometry(view.map_xy(rows));
	const Eigen::VectorXd nu = relative::relativeDifference(z.value, h.value);	 // eq. (3.43)
	Eigen::MatrixXd S = h.jacobian * view.map_cov(rows, rows) * h.jacobian.transpose() +
		z.jacobian * view.measured.cov(rows, rows) * z.jacobian.transpose();  // eq. (3.44)
	S = 0.5 * (S + S.transpose()).eval();
	const Eigen::LDLT<Eigen::MatrixXd> ldlt(S);
	if (ldlt.info() != Eigen::Success) return {std::numeric_limits<double>::infinity(), static_cast<int>(nu.size())};
	return {nu.dot(ldlt.solve(nu)), static_cast<int>(nu.size())};
}

std::vector<int> mappedOutliers(const MappedView& view, double quantile)
{
	std::vector<int> keep(static_cast<std::size_t>(view.measured.size()));
	for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = static_cast<int>(i);
	std::vector<int> rejected;
	const auto passes = [&](const std::pair<double, int>& d) { return d.first <= chi2Quantile(quantile, d.second); };
	while (keep.size() >= 2 && !passes(relativeDistance2(view, keep)))
	{
		if (keep.size() == 2)
		{
			rejected.insert(rejected.end(), keep.begin(), keep.end());	// their distance contradicts the map
			break;
		}
		// Remove the point whose absence leaves the smallest normalised distance (eq. 3.45, eq. 3.43-3.44
		// being invariant to the choice of the pair up to linearisation).
		std::size_t worst = 0;
		double best = std::numeric_limits<double>::infinity();
		for (std::size_t j = 0; j < keep.size(); ++j)
		{
			std::vector<int> rest = keep;
			rest.erase(rest.begin() + static_cast<long>(j));
			const auto d = relativeDistance2(view, rest);
			const double normalised = d.first / chi2Quantile(quantile, d.second);
			if (normalised < best)
			{
				best = normalised;
				worst = j;
			}
		}
		rejected.push_back(keep[worst]);
		keep.erase(keep.begin() + static_cast<long>(worst));
	}
	return rejected;
}

}  // namespace esif::dslam
