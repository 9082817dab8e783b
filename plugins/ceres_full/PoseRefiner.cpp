#include "PoseRefiner.h"

#include "QuietCeresLogging.h"
#include "Residuals.h"

namespace esif::ceres_full
{
namespace
{
ceres::Problem::Options ownLossNot()
{
	ceres::Problem::Options o;
	o.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;  // the graph's loss, shared
	o.enable_fast_removal = false;
	return o;
}

ceres::Solver::Options threeUnknowns()
{
	ceres::Solver::Options o;
	o.linear_solver_type = ceres::DENSE_QR;
	// The start is odometry away from the optimum: a few steps reach it, and
	// the next re-solve polishes it anyway.
	o.max_num_iterations = 5;
	o.function_tolerance = 1e-6;
	o.num_threads = 1;
	o.logging_type = ceres::SILENT;
	return o;
}
}  // namespace

Pose2 refineNewPose(
	const Pose2& previous, const OdometryIncrement& odometry, const Pose2& initial,
	const std::vector<MappedMeasurement>& seen, const ceres::LossFunction* loss)
{
	Eigen::Matrix3d w_odometry;
	if (seen.empty() || !sqrtInformation<3>(odometry.cov, w_odometry)) return initial;
	ceres::Problem problem(ownLossNot());
	Pose2 prev = previous, pose = initial;
	std::vector<Eigen::Vector2d> landmarks;
	landmarks.reserve(seen.size());  // parameter blocks must not move
	problem.AddResidualBlock(OdometryResidual::create(odometry.delta, w_odometry), nullptr, prev.data(), pose.data());
	problem.SetParameterBlockConstant(prev.data());
	for (const MappedMeasurement& s : seen)
	{
		Eigen::Matrix2d w;
		if (!sqrtInformation<2>(s.measurement.cov, w)) continue;
		landmarks.push_back(s.landmark);
		problem.AddResidualBlock(
			RangeBearingResidual::create(
				Eigen::Vector2d(s.measurement.range_m, s.measurement.bearing_rad), w, s.sensor_on_robot),
			const_cast<ceres::LossFunction*>(loss), pose.data(), landmarks.back().data());
		problem.SetParameterBlockConstant(landmarks.back().data());
	}
	ceres::Solver::Summary summary;
	{
		// A start on a landmark evaluates to NaN: the fallback below is the
		// answer, glog's dump of the residual block would only be noise.
		const QuietCeresLogging quiet;
		ceres::Solve(threeUnknowns(), &problem, &summary);
	}
	if (summary.termination_type == ceres::FAILURE || !pose.allFinite()) return initial;
	pose.z() = esif::wrapAngle(pose.z());
	return pose;
}

}  // namespace esif::ceres_full
