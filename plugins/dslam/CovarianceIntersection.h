#pragma once
/// \file CovarianceIntersection.h
/// Covariance intersection of two estimates of one state whose correlation
/// is unknown (book Sec. 3.1.4.4, eq. 3.20-3.21), with the weight w in
/// [0, 1] that minimises the trace of the robot-pose block of the result
/// (metres and radians unscaled, as the book suggests).

#include "KidnappedRobot.h"

namespace esif::dslam
{
struct CiResult
{
	GaussianState fused;
	double omega = 0;  ///< weight of the first estimate
};

/// Fuses `a` (weight w) and `b` (1 - w); both laid out [robot(3); ...] in
/// the same order. b's heading is first brought within pi of a's.
CiResult covarianceIntersection(const GaussianState& a, const GaussianState& b);

/// The first three entries (the robot pose) of a state, as a state.
GaussianState robotMarginal(const GaussianState& s);

/// The first n entries of a state (the robot, then the first features).
GaussianState leadingMarginal(const GaussianState& s, Eigen::Index n);

/// Replaces the marginal of the first entries of `s` (the robot, and
/// possibly the first features) by `lead` and keeps the conditional of the
/// other entries given them:
///   x_f += K (x_l' - x_l),  K = P_fl P_ll^-1,
///   P_fl' = K P_l',  P_ff' = P_ff - K P_lf + K P_l' K^T.
/// Used to carry a fusion of the robot (or of the robot and the features in
/// view) over to the local SLAM's other features.
GaussianState withLeadingMarginal(const GaussianState& s, const GaussianState& lead);

}  // namespace esif::dslam
