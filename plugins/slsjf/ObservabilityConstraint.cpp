#include "ObservabilityConstraint.h"

#include <Eigen/Cholesky>
#include <stdexcept>

namespace esif::slsjf
{
Eigen::MatrixXd rigidMotionDirections(const std::vector<Eigen::VectorXd>& points)
{
	Eigen::Index rows = 0;
	for (const auto& p : points) rows += p.size();
	Eigen::MatrixXd N = Eigen::MatrixXd::Zero(rows, 3);
	Eigen::Index at = 0;
	for (const auto& p : points)
	{
		if (p.size() != 2 && p.size() != 3)
			throw std::logic_error("rigidMotionDirections: a variable of dimension " + std::to_string(p.size()));
		N(at, 0) = N(at + 1, 1) = 1;
		N(at, 2) = -p(1);  // d/dtheta of R(theta) p at theta = 0
		N(at + 1, 2) = p(0);
		if (p.size() == 3) N(at + 2, 2) = 1;  // the heading turns with the frame
		at += p.size();
	}
	return N;
}

Eigen::MatrixXd constrainToNullSpace(const Eigen::MatrixXd& J, const Eigen::MatrixXd& N)
{
	const Eigen::MatrixXd NtN = N.transpose() * N;	// 3 x 3
	return J - (J * N) * NtN.llt().solve(N.transpose());
}

}  // namespace esif::slsjf
