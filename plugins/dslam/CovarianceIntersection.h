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

/// Replaces the robot marginal of `s` by `robot` and keeps the conditional
/// of the other entries given the robot:
///   x_f += K (x_r' - x_r),  K = P_fr P_rr^-1,
///   P_fr' = K P_r',  P_ff' = P_ff - K P_rf + K P_r' K^T.
/// Used to carry a robot-only fusion over to the local SLAM's features.
GaussianState withRobotMarginal(const GaussianState& s, const GaussianState& robot);

}  // namespace esif::dslam
