#pragma once
/// \file KidnappedTestCase.h
/// The hand-computable kidnapped-robot case (book eq. 3.17-3.18) shared by
/// the D-SLAM unit tests: robot truly at the origin heading 0, features
/// f1 = (2, 0) and f2 = (0, 2) with independent covariances sigma_f^2 I,
/// exact measurements r = 2 at bearings 0 and pi/2.

#include "KidnappedRobot.h"

#include <cmath>

namespace esif::dslam::cases
{
constexpr double kSigmaF = 0.05, kSigmaR = 0.1, kSigmaT = 0.02;

inline KidnappedInput twoFeatureCase()
{
	KidnappedInput in;
	in.features = (Eigen::VectorXd(4) << 2, 0, 0, 2).finished();
	in.features_cov = kSigmaF * kSigmaF * Eigen::MatrixXd::Identity(4, 4);
	const Eigen::Matrix2d R = Eigen::Vector2d(kSigmaR * kSigmaR, kSigmaT * kSigmaT).asDiagonal();
	in.z_loc = {{1, Eigen::Vector2d(2, 0), R}, {2, Eigen::Vector2d(2, M_PI / 2), R}};
	in.initial_robot = Pose2::Zero();
	return in;
}

}  // namespace esif::dslam::cases
