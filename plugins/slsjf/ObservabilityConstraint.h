#pragma once
/// \file ObservabilityConstraint.h
/// Observability-constrained Jacobians for SLSJF's fusions (after Huang,
/// Mourikis & Roumeliotis, "Observability-based rules for designing
/// consistent EKF SLAM estimators", IJRR 2010). A local map observed from
/// a start pose that is itself a variable (eq. 5.8) is a relative
/// observation: moving the whole map rigidly (a translation, a rotation
/// about the origin) does not change it, so its Jacobian J satisfies
/// J N(x) = 0 at the point x it is taken at. Maps linearised at different
/// estimates of the same variables have different N(x), and together
/// inform the rigid motion no map observes: spurious information, the
/// over-confident rotation of the book's filter. First-estimates Jacobians
/// share one N but take J at points that can be metres away after a loop
/// closes; here J is taken at the current estimate and projected, by the
/// smallest change in the Frobenius norm, onto J N_fe = 0 with N_fe at the
/// first estimates, the one null space every fusion then shares.

#include <Eigen/Core>
#include <vector>

namespace esif::slsjf
{
/// The rigid motions of the plane as columns (translation x, y; rotation
/// about the origin) over variables of dimension 3 (poses x, y, phi) or 2
/// (points x, y), stacked in order, each at `points[i]`.
Eigen::MatrixXd rigidMotionDirections(const std::vector<Eigen::VectorXd>& points);

/// J - J N (N^T N)^-1 N^T: the Jacobian closest to `J` with `N` in its
/// null space. N must have full column rank (it has: the translation
/// columns are independent at any point).
Eigen::MatrixXd constrainToNullSpace(const Eigen::MatrixXd& J, const Eigen::MatrixXd& N);

}  // namespace esif::slsjf
