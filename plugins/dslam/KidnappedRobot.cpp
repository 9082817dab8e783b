#include "KidnappedRobot.h"

#include <esif/core/Errors.h>
#include <esif/models/RangeBearingModel.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace esif::dslam
{
namespace
{
/// Eq. (3.17) linearised at y: the prior information plus z_loc's.
struct NormalEquations
{
	Eigen::MatrixXd info;
	Eigen::VectorXd eta;
};

/// Measurement i of z_loc predicted at the state y = [robot; features],
/// and its residual z - h(y), bearing wrapped.
struct Prediction
{
	RangeBearingPrediction h;
	Eigen::Vector2d residual;
};

Prediction predicted(const KidnappedInput& in, const Eigen::VectorXd& y, std::size_t i)
{
	Prediction p{predictRangeBearing(y.head<3>(), in.sensor_on_robot, y.segment<2>(3 + 2 * static_cast<int>(i))), {}};
	p.residual = in.z_loc[i].z - p.h.z;
	p.residual(1) = wrapAngle(p.residual(1));
	return p;
}

NormalEquations linearisedAt(const KidnappedInput& in, const Eigen::VectorXd& y, const NormalEquations& prior)
{
	NormalEquations ne = prior;
	const int n = static_cast<int>(y.size());
	for (std::size_t i = 0; i < in.z_loc.size(); ++i)
	{
		const auto [h, nu] = predicted(in, y, i);
		Eigen::Matrix<double, 2, Eigen::Dynamic> H = Eigen::MatrixXd::Zero(2, n);
		H.leftCols<3>() = h.d_robot;
		H.middleCols<2>(3 + 2 * static_cast<int>(i)) = h.d_landmark;
		const Eigen::Matrix2d Rinv = in.z_loc[i].R.inverse();  // 2x2 measurement noise
		ne.info.noalias() += H.transpose() * Rinv * H;
		ne.eta.noalias() += H.transpose() * Rinv * (nu + H * y);
	}
	return ne;
}
}  // namespace

GaussianState solveKidnappedRobot(const KidnappedInput& in)
{
	const int m1 = static_cast<int>(in.z_loc.size());
	const int n = 3 + 2 * m1;
	if (m1 < 2 || in.features.size() != 2 * m1)
		throw NumericalError("kidnapped robot: needs at least two mapped features in view");

	// Linearisation point: robot by eq. (3.18), features from the map.
	Eigen::VectorXd y(n);
	y << in.initial_robot, in.features;

	// Prior information: zero on the robot, the map's on the features.
	const Eigen::LLT<Eigen::MatrixXd> prior_llt(in.features_cov);
	if (prior_llt.info() != Eigen::Success)
		throw NumericalError("kidnapped robot: map covariance not positive definite");
	NormalEquations prior{Eigen::MatrixXd::Zero(n, n), Eigen::VectorXd::Zero(n)};
	prior.info.bottomRightCorner(2 * m1, 2 * m1) = prior_llt.solve(Eigen::MatrixXd::Identity(2 * m1, 2 * m1));
	prior.eta = prior.info * y;	 // the prior mean is y's feature part

	// Converged when a step moves the robot less than these: far below the
	// measurement noise.
	constexpr double kConvergedM = 1e-3, kConvergedRad = 1e-6;
	GaussianState out;
	Eigen::LLT<Eigen::MatrixXd> llt;
	for (int it = 0; it < std::max(1, in.iterations); ++it)
	{
		const NormalEquations ne = linearisedAt(in, y, prior);
		llt.compute(ne.info);
		if (llt.info() != Eigen::Success) throw NumericalError("kidnapped robot: the robot pose is not observable");
		out.mean = llt.solve(ne.eta);
		out.mean(2) = y(2) + wrapAngle(out.mean(2) - y(2));
		Eigen::VectorXd step = out.mean - y;
		y = out.mean;
		if (step.head<2>().norm() < kConvergedM && std::abs(step(2)) < kConvergedRad) break;
	}
	out.mean(2) = wrapAngle(out.mean(2));
	// The covariance of the last linearisation, the one the mean came from.
	out.cov = llt.solve(Eigen::MatrixXd::Identity(n, n));  // (3 + 2 m1)^2: small by construction
	out.cov = 0.5 * (out.cov + out.cov.transpose()).eval();
	return out;
}

double kidnappedFitChi2(const KidnappedInput& in, const GaussianState& solution)
{
	double chi2 = 0;
	for (std::size_t i = 0; i < in.z_loc.size(); ++i)
	{
		const Eigen::Vector2d nu = predicted(in, solution.mean, i).residual;
		chi2 += nu.dot(in.z_loc[i].R.ldlt().solve(nu));
	}
	const Eigen::VectorXd df = solution.mean.tail(in.features.size()) - in.features;
	return chi2 + df.dot(in.features_cov.ldlt().solve(df));
}

}  // namespace esif::dslam
