#pragma once
/// \file KidnappedRobot.h
/// D-SLAM's second localisation process (book Sec. 3.1.4.2, Fig. 3.4 steps
/// F-G): the robot pose from the current map alone, discarding all
/// knowledge of where the robot was ("kidnapped robot").
///
/// The state is [X_r, X_1, ..., X_m1] for the m1 >= 2 mapped features in
/// view. Their map estimate and joint covariance are the prior; the robot
/// starts with zero information at the pose given by eq. (3.18) from the
/// reference pair, then the state is updated once with z_loc, eq. (3.17),
/// as a linearised minimum-mean-square-error estimate in information form.

#include "LocalSlam.h"

#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <vector>

namespace esif::dslam
{
struct KidnappedInput
{
	Eigen::VectorXd features;  ///< map estimates of f1..fm1, stacked (2 m1)
	Eigen::MatrixXd features_cov;  ///< their joint covariance from the map
	std::vector<IdentifiedMeasurement> z_loc;  ///< measurements of f1..fm1, same order
	Pose2 initial_robot;  ///< eq. (3.18)
	Pose2 sensor_on_robot = Pose2::Zero();
};

struct GaussianState
{
	Eigen::VectorXd mean;  ///< [robot (3); features (2 each)]
	Eigen::MatrixXd cov;
};

/// Eq. (3.17)-(3.18). Throws NumericalError if the robot pose is not
/// observable from the measurements (e.g. fewer than two features).
GaussianState solveKidnappedRobot(const KidnappedInput& in);

}  // namespace esif::dslam
