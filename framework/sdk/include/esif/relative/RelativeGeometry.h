#pragma once
/// \file RelativeGeometry.h
/// D-SLAM's measurement recasting (book Sec. 3.1.1) as plain functions of
/// point positions. In the framework because it serves both D-SLAM (Ch. 3),
/// which recasts scans, and D-SLAM map joining (Ch. 4), which recasts local
/// maps the same way:
/// - T1, eq. (3.4)/(3.7): range-bearing measurements -> feature points in the
///   robot frame, with the Jacobian that carries their covariance over;
/// - T2 = H_map = G, eq. (3.8)/(3.13)/(3.40): distances and angles among
///   features relative to a reference pair (f1, f2). The same function maps
///   measured points to z_map and map estimates to H_map(X), so one
///   implementation (and one Jacobian) serves the map update, eq. (3.15),
///   and the association test, eq. (3.43)-(3.45);
/// - z_rob, eq. (3.3)/(3.6), and its inverse eq. (3.18) (the robot pose from
///   two mapped features), and new-feature initialisation, eq. (3.14).
///
/// Point lists are always ordered [f1, f2, f3, ..., fm]: the reference pair
/// first. z_map = [d12, a312, d13, a412, d14, ...]: 2m - 3 entries, angles at
/// the odd indices.

#include <esif/core/StepInput.h>
#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <vector>

namespace esif::relative
{
/// Points stacked as [x1, y1, x2, y2, ...] with their joint covariance.
struct PointSet
{
	Eigen::VectorXd xy;
	Eigen::MatrixXd cov;

	int size() const { return static_cast<int>(xy.size() / 2); }
	Eigen::Vector2d point(int i) const { return xy.segment<2>(2 * i); }
};

/// The points `order` (indices into `p`), in that order, with their joint
/// covariance: e.g. the reference pair moved to the front.
PointSet selectPoints(const PointSet& p, const std::vector<int>& order);

/// `order` = [first, second, then every other index of 0..n-1 ascending].
std::vector<int> pairFirst(int n, int first, int second);

/// T1: measurements (range, bearing; the sensor at `sensor_on_robot`) ->
/// points in the robot frame. `cov` is the joint covariance of the stacked
/// (range, bearing) pairs (block diagonal for a real scan, full for a
/// virtual observation); the result carries dT1 cov dT1^T.
PointSet pointsInRobotFrame(const Eigen::VectorXd& range_bearing, const Eigen::MatrixXd& cov,
							const Pose2& sensor_on_robot);

/// A vector function value with its Jacobian.
struct ValueJacobian
{
	Eigen::VectorXd value;
	Eigen::MatrixXd jacobian;
};

/// T2 / H_map / G, eq. (3.8), (3.13), (3.40): z_map of the points, with the
/// Jacobian with respect to all of them ((2m - 3) x 2m). Angles wrapped.
ValueJacobian relativeGeometry(const Eigen::VectorXd& xy);
/// The same z_map without its Jacobian (a cost evaluation needs no more).
Eigen::VectorXd relativeGeometryValue(const Eigen::VectorXd& xy);

/// Indices of the angle entries of a z_map of m points (1, 3, 5, ...).
bool isAngleEntry(int index);
/// a - b for z_map vectors, the angle entries wrapped.
Eigen::VectorXd relativeDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

/// z_rob = (a_r12, d_1r, a_phi12), eq. (3.3)/(3.6): the robot relative to
/// f1 and the baseline f1 -> f2, from f1 and f2 in the robot frame.
Eigen::Vector3d robotRelativeToPair(const Eigen::Vector2d& f1, const Eigen::Vector2d& f2);

/// Eq. (3.18): the robot pose in the map frame from the map positions of f1,
/// f2 and z_rob.
Pose2 robotFromPair(const Eigen::Vector2d& f1, const Eigen::Vector2d& f2, const Eigen::Vector3d& z_rob);

/// Eq. (3.14): map position of a new feature fi from the map positions of
/// f1, f2 and its (d_1i, a_i12).
Eigen::Vector2d featureFromPair(const Eigen::Vector2d& f1, const Eigen::Vector2d& f2, double d_1i, double a_i12);

}  // namespace esif::relative
