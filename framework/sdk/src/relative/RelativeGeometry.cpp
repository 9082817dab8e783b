#include <esif/relative/RelativeGeometry.h>

#include <cmath>

namespace esif::relative
{
namespace
{
/// Direction angle of v and its gradient d angle / d v.
double angleOf(const Eigen::Vector2d& v, Eigen::RowVector2d& grad)
{
	const double n2 = v.squaredNorm();
	grad << -v.y() / n2, v.x() / n2;
	return std::atan2(v.y(), v.x());
}

/// Length of v and its gradient d |v| / d v.
double lengthOf(const Eigen::Vector2d& v, Eigen::RowVector2d& grad)
{
	const double n = v.norm();
	grad = v.transpose() / n;
	return n;
}
}  // namespace

PointSet selectPoints(const PointSet& p, const std::vector<int>& order)
{
	std::vector<Eigen::Index> rows;
	rows.reserve(2 * order.size());
	for (int i : order)
	{
		rows.push_back(2 * i);
		rows.push_back(2 * i + 1);
	}
	return {p.xy(rows), p.cov(rows, rows)};
}

std::vector<int> pairFirst(int n, int first, int second)
{
	std::vector<int> order = {first, second};
	for (int i = 0; i < n; ++i)
		if (i != first && i != second) order.push_back(i);
	return order;
}

PointSet pointsInRobotFrame(const Eigen::VectorXd& range_bearing, const Eigen::MatrixXd& cov,
							const Pose2& sensor_on_robot)
{
	// Eq. (3.7) with the sensor's mounting: p = R_s (r cos t, r sin t) + t_s.
	const int m = static_cast<int>(range_bearing.size() / 2);
	const double c = std::cos(sensor_on_robot.z()), s = std::sin(sensor_on_robot.z());
	Eigen::Matrix2d Rs;
	Rs << c, -s, s, c;
	PointSet out;
	out.xy.resize(2 * m);
	Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * m, 2 * m);  // dT1, block diagonal
	for (int i = 0; i < m; ++i)
	{
		const double r = range_bearing(2 * i), t = range_bearing(2 * i + 1);
		out.xy.segment<2>(2 * i) = Rs * Eigen::Vector2d(r * std::cos(t), r * std::sin(t)) + sensor_on_robot.head<2>();
		Eigen::Matrix2d d;
		d << std::cos(t), -r * std::sin(t), std::sin(t), r * std::cos(t);
		J.block<2, 2>(2 * i, 2 * i) = Rs * d;
	}
	out.cov = J * cov * J.transpose();
	out.cov = 0.5 * (out.cov + out.cov.transpose()).eval();
	return out;
}

namespace
{
/// Eq. (3.8): d12, then (a_i12, d_1i) for i = 3..m, all relative to f1;
/// with the Jacobian when `jacobian` is given.
Eigen::VectorXd relativeGeometryOf(const Eigen::VectorXd& xy, Eigen::MatrixXd* jacobian)
{
	const int m = static_cast<int>(xy.size() / 2);
	Eigen::VectorXd value(2 * m - 3);
	if (jacobian) *jacobian = Eigen::MatrixXd::Zero(2 * m - 3, 2 * m);
	const Eigen::Vector2d f1 = xy.head<2>();
	Eigen::RowVector2d g_base, g;
	const double base = angleOf(xy.segment<2>(2) - f1, g_base);
	value(0) = lengthOf(xy.segment<2>(2) - f1, g);
	if (jacobian)
	{
		jacobian->block<1, 2>(0, 0) = -g;
		jacobian->block<1, 2>(0, 2) = g;
	}
	for (int i = 2; i < m; ++i)
	{
		const int row = 2 * i - 3;	// a_i12, then d_1i
		const Eigen::Vector2d v = xy.segment<2>(2 * i) - f1;
		value(row) = wrapAngle(angleOf(v, g) - base);
		if (jacobian)
		{
			jacobian->block<1, 2>(row, 2 * i) = g;
			jacobian->block<1, 2>(row, 0) = -g + g_base;
			jacobian->block<1, 2>(row, 2) = -g_base;
		}
		value(row + 1) = lengthOf(v, g);
		if (jacobian)
		{
			jacobian->block<1, 2>(row + 1, 2 * i) = g;
			jacobian->block<1, 2>(row + 1, 0) = -g;
		}
	}
	return value;
}
}  // namespace

ValueJacobian relativeGeometry(const Eigen::VectorXd& xy)
{
	ValueJacobian out;
	out.value = relativeGeometryOf(xy, &out.jacobian);
	return out;
}

Eigen::VectorXd relativeGeometryValue(const Eigen::VectorXd& xy) { return relativeGeometryOf(xy, nullptr); }

bool isAngleEntry(int index) { return index % 2 == 1; }

Eigen::VectorXd relativeDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& b)
{
	Eigen::VectorXd d = a - b;
	for (int i = 1; i < d.size(); i += 2) d(i) = wrapAngle(d(i));
	return d;
}

Eigen::Vector3d robotRelativeToPair(const Eigen::Vector2d& f1, const Eigen::Vector2d& f2)
{
	// Eq. (3.3), first three rows, with the robot at the origin heading 0.
	const Eigen::Vector2d base = f2 - f1;
	const double beta = std::atan2(base.y(), base.x());
	return {wrapAngle(std::atan2(-f1.y(), -f1.x()) - beta), f1.norm(), wrapAngle(-beta)};
}

Pose2 robotFromPair(const Eigen::Vector2d& f1, const Eigen::Vector2d& f2, const Eigen::Vector3d& z_rob)
{
	// Eq. (3.18).
	const double beta = std::atan2(f2.y() - f1.y(), f2.x() - f1.x());
	return {f1.x() + z_rob(1) * std::cos(beta + z_rob(0)), f1.y() + z_rob(1) * std::sin(beta + z_rob(0)),
			wrapAngle(beta + z_rob(2))};
}

Eigen::Vector2d featureFromPair(const Eigen::Vector2d& f1, const Eigen::Vector2d& f2, double d_1i, double a_i12)
{
	// Eq. (3.14).
	const double beta = std::atan2(f2.y() - f1.y(), f2.x() - f1.x());
	return f1 + d_1i * Eigen::Vector2d(std::cos(beta + a_i12), std::sin(beta + a_i12));
}

}  // namespace esif::relative
