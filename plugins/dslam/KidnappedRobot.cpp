#include "KidnappedRobot.h"

#include <esif/core/Errors.h>
#include <esif/models/RangeBearingModel.h>

#include <Eigen/Dense>

namespace esif::dslam
{
GaussianState solveKidnappedRobot(const KidnappedInput& in)
{
	const int m1 = static_cast<int>(in.z_loc.size());
	const int n = 3 + 2 * m1;
	if (m1 < 2 || in.features.size() != 2 * m1)
		throw NumericalError("kidnapped robot: needs at least two mapped features in view");

	// Linearisation point: robot by eq. (3.18), features from the map.
	Eigen::VectorXd y0(n);
	y0 << in.initial_robot, in.features;

	// Prior information: zero on the robot, the map's on the features.
	const Eigen::LLT<Eigen::MatrixXd> prior(in.features_cov);
	if (prior.info() != Eigen::Success) throw NumericalError("kidnapped robot: map covariance not positive definite");
	Eigen::MatrixXd info = Eigen::MatrixXd::Zero(n, n);
	info.bottomRightCorner(2 * m1, 2 * m1) = prior.solve(Eigen::MatrixXd::Identity(2 * m1, 2 * m1));
	Eigen::VectorXd eta = info * y0;  // the prior mean is y0's feature part

	// Update with z_loc, eq. (3.17): information-form EIF step at y0.
	for (int i = 0; i < m1; ++i)
	{
		const auto h = predictRangeBearing(y0.head<3>(), in.sensor_on_robot, y0.segment<2>(3 + 2 * i));
		Eigen::Matrix<double, 2, Eigen::Dynamic> H = Eigen::MatrixXd::Zero(2, n);
		H.leftCols<3>() = h.d_robot;
		H.middleCols<2>(3 + 2 * i) = h.d_landmark;
		Eigen::Vector2d nu = in.z_loc[i].z - h.z;
		nu(1) = wrapAngle(nu(1));
		const Eigen::Matrix2d Rinv = in.z_loc[i].R.inverse();  // 2x2 measurement noise
		info.noalias() += H.transpose() * Rinv * H;
		eta.noalias() += H.transpose() * Rinv * (nu + H * y0);
	}

	const Eigen::LLT<Eigen::MatrixXd> llt(info);
	if (llt.info() != Eigen::Success) throw NumericalError("kidnapped robot: the robot pose is not observable");
	GaussianState out;
	out.mean = llt.solve(eta);
	out.mean(2) = wrapAngle(out.mean(2));
	out.cov = llt.solve(Eigen::MatrixXd::Identity(n, n));  // (3 + 2 m1)^2: small by construction
	out.cov = 0.5 * (out.cov + out.cov.transpose()).eval();
	return out;
}

}  // namespace esif::dslam
