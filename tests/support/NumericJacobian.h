#pragma once
/// \file NumericJacobian.h
/// Central finite differences, for checking every analytic Jacobian.

#include <Eigen/Core>
#include <functional>

namespace esif::test
{
/// d f / d x at x, by central differences with step h. `wrap_rows` marks
/// output rows that are angles, whose differences are wrapped to (-pi, pi].
inline Eigen::MatrixXd numericJacobian(
	const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x, double h = 1e-6,
	const std::vector<int>& wrap_rows = {})
{
	const Eigen::VectorXd f0 = f(x);
	Eigen::MatrixXd J(f0.size(), x.size());
	for (Eigen::Index i = 0; i < x.size(); ++i)
	{
		Eigen::VectorXd xp = x, xm = x;
		xp(i) += h;
		xm(i) -= h;
		Eigen::VectorXd d = f(xp) - f(xm);
		for (int r : wrap_rows) d(r) = std::remainder(d(r), 2 * M_PI);
		J.col(i) = d / (2 * h);
	}
	return J;
}

}  // namespace esif::test
