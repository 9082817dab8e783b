#pragma once
/// \file Residuals.h
/// The two terms of the full-SLAM negative log posterior (book eq. 1.21), as
/// Ceres cost functors: each residual is whitened by the square-root
/// information of its noise, so that 2 x (Ceres cost) is the sum of squared
/// Mahalanobis distances, chi-square with (residuals - parameters) degrees
/// of freedom at the optimum.

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>

namespace esif::ceres_full
{
/// a wrapped to [-pi, pi); with Jets the derivative passes through unchanged.
template <typename T>
T wrapAngle(const T& a)
{
	const T two_pi = T(2.0 * M_PI);
	return a - two_pi * ceres::floor((a + T(M_PI)) / two_pi);
}

/// W with W^T W = cov^-1, without forming the inverse: for cov = L L^T,
/// W = L^-1. Returns false when cov is not symmetric positive definite.
template <int N>
bool sqrtInformation(const Eigen::Matrix<double, N, N>& cov, Eigen::Matrix<double, N, N>& w)
{
	const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(0.5 * (cov + cov.transpose()));
	if (llt.info() != Eigen::Success || !cov.allFinite()) return false;
	w = llt.matrixL().solve(Eigen::Matrix<double, N, N>::Identity());
	return true;
}

/// Process-model term (eq. 1.19): pose j = pose i (+) (u + w) with w ~ N(0, Q)
/// in the frame of pose i, so the residual W (pose_i (-) pose_j - u), angle
/// wrapped, is exactly the whitened noise w.
struct OdometryResidual
{
	OdometryResidual(const Eigen::Vector3d& delta, const Eigen::Matrix3d& sqrt_info)
		: delta_(delta), sqrt_info_(sqrt_info)
	{
	}

	template <typename T>
	bool operator()(const T* pose_i, const T* pose_j, T* residual) const
	{
		const T dx = pose_j[0] - pose_i[0], dy = pose_j[1] - pose_i[1];
		const T c = ceres::cos(pose_i[2]), s = ceres::sin(pose_i[2]);
		Eigen::Matrix<T, 3, 1> e;
		e << c * dx + s * dy - T(delta_.x()), -s * dx + c * dy - T(delta_.y()),
			wrapAngle(pose_j[2] - pose_i[2] - T(delta_.z()));
		Eigen::Map<Eigen::Matrix<T, 3, 1>> r(residual);
		r = sqrt_info_.cast<T>() * e;
		return true;
	}

	static ceres::CostFunction* create(const Eigen::Vector3d& delta, const Eigen::Matrix3d& sqrt_info)
	{
		return new ceres::AutoDiffCostFunction<OdometryResidual, 3, 3, 3>(new OdometryResidual(delta, sqrt_info));
	}

   private:
	Eigen::Vector3d delta_;	 ///< (dx, dy, dphi)
	Eigen::Matrix3d sqrt_info_;
};

/// Observation term (eq. 1.20 with the range-bearing model eq. 1.6): the
/// sensor sits at `sensor_on_robot` in the robot frame; the residual is
/// W (h(robot, landmark) - z), bearing wrapped.
struct RangeBearingResidual
{
	RangeBearingResidual(const Eigen::Vector2d& z, const Eigen::Matrix2d& sqrt_info, const Eigen::Vector3d& sensor)
		: z_(z), sqrt_info_(sqrt_info), sensor_(sensor)
	{
	}

	template <typename T>
	bool operator()(const T* robot, const T* landmark, T* residual) const
	{
		const T c = ceres::cos(robot[2]), s = ceres::sin(robot[2]);
		// Sensor pose in the world: robot (+) sensor_on_robot.
		const T sx = robot[0] + c * T(sensor_.x()) - s * T(sensor_.y());
		const T sy = robot[1] + s * T(sensor_.x()) + c * T(sensor_.y());
		const T dx = landmark[0] - sx, dy = landmark[1] - sy;
		const T range = ceres::sqrt(dx * dx + dy * dy);
		const T bearing = ceres::atan2(dy, dx) - robot[2] - T(sensor_.z());
		Eigen::Matrix<T, 2, 1> e;
		e << range - T(z_.x()), wrapAngle(bearing - T(z_.y()));
		Eigen::Map<Eigen::Matrix<T, 2, 1>> r(residual);
		r = sqrt_info_.cast<T>() * e;
		return true;
	}

	static ceres::CostFunction* create(
		const Eigen::Vector2d& z, const Eigen::Matrix2d& sqrt_info, const Eigen::Vector3d& sensor)
	{
		return new ceres::AutoDiffCostFunction<RangeBearingResidual, 2, 3, 2>(
			new RangeBearingResidual(z, sqrt_info, sensor));
	}

   private:
	Eigen::Vector2d z_;	 ///< (range [m], bearing [rad])
	Eigen::Matrix2d sqrt_info_;
	Eigen::Vector3d sensor_;  ///< sensor pose on the robot (x, y, phi)
};

}  // namespace esif::ceres_full
