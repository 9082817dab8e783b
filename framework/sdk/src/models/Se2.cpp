#include <esif/models/Se2.h>

#include <cmath>

namespace esif
{
double wrapAngle(double a)
{
	// Most angles are in range already: remainder() returns them unchanged,
	// at many times the cost of the test.
	if (a > -M_PI && a <= M_PI) return a;
	// remainder() maps to [-pi, pi]; fold -pi onto pi for a half-open range.
	double r = std::remainder(a, 2.0 * M_PI);
	return r <= -M_PI ? r + 2.0 * M_PI : r;
}

Pose2 toPose2(const mrpt::math::TPose2D& p) { return {p.x, p.y, p.phi}; }

mrpt::math::TPose2D toTPose2D(const Pose2& p) { return {p.x(), p.y(), p.z()}; }

Pose2 compose(const Pose2& a, const Pose2& b)
{
	const double c = std::cos(a.z()), s = std::sin(a.z());
	return {a.x() + c * b.x() - s * b.y(), a.y() + s * b.x() + c * b.y(), wrapAngle(a.z() + b.z())};
}

Pose2 inverseCompose(const Pose2& a, const Pose2& b)
{
	const double c = std::cos(a.z()), s = std::sin(a.z());
	const double dx = b.x() - a.x(), dy = b.y() - a.y();
	return {c * dx + s * dy, -s * dx + c * dy, wrapAngle(b.z() - a.z())};
}

ComposeJacobians composeJacobians(const Pose2& a, const Pose2& b)
{
	const double c = std::cos(a.z()), s = std::sin(a.z());
	ComposeJacobians J;
	J.d_a << 1, 0, -s * b.x() - c * b.y(),  //
		0, 1, c * b.x() - s * b.y(),  //
		0, 0, 1;
	J.d_b << c, -s, 0,	//
		s, c, 0,  //
		0, 0, 1;
	return J;
}

Eigen::Vector2d transformPoint(const Pose2& pose, const Eigen::Vector2d& p)
{
	const double c = std::cos(pose.z()), s = std::sin(pose.z());
	return {pose.x() + c * p.x() - s * p.y(), pose.y() + s * p.x() + c * p.y()};
}

PoseEstimate composeIndependent(const PoseEstimate& x, const PoseEstimate& r)
{
	const Pose2& a = x.mean;
	const Pose2& b = r.mean;
	const auto J = composeJacobians(a, b);
	const Eigen::Matrix3d P = J.d_a * x.cov * J.d_a.transpose() + J.d_b * r.cov * J.d_b.transpose();
	return {compose(a, b), 0.5 * (P + P.transpose())};
}

}  // namespace esif
