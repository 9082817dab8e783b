#pragma once
/// \file KidnappedRobot.h
/// D-SLAM's second localisation process (book Sec. 3.1.4.2, Fig. 3.4 steps
/// F-G): the robot pose from the current map alone, discarding all
/// knowledge of where the robot was ("kidnapped robot").
///
/// The state is [X_r, X_1, ..., X_m1] for the m1 >= 2 mapped features in
/// view. Their map estimate and joint covariance are the prior; the robot
/// starts with zero information at the pose given by eq. (3.18) from the
/// reference pair, then the state is updated with z_loc, eq. (3.17), as a
/// linearised minimum-mean-square-error estimate in information form. The
/// book takes one step; with `iterations` > 1 the step is repeated from its
/// own result (Gauss-Newton on the prior plus z_loc) until it stops moving,
/// which matters when eq. (3.18) starts far off: a pair of one old feature
/// and one mapped after a long gap, metres off before the loop closes.

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
	int iterations = 1;	 ///< Gauss-Newton iterations; 1 = the book's single step
};

struct GaussianState
{
	Eigen::VectorXd mean;  ///< [robot (3); features (2 each)]
	Eigen::MatrixXd cov;
};

/// Eq. (3.17)-(3.18). Throws NumericalError if the robot pose is not
/// observable from the measurements (e.g. fewer than two features).
GaussianState solveKidnappedRobot(const KidnappedInput& in);

/// How well the map and z_loc fit together at `solution`: the cost of eq.
/// (3.17)'s problem there, sum over z_loc of the squared normalised
/// residuals plus the features' squared normalised departure from the map,
/// chi-square with 2 m1 - 3 degrees of freedom (dof(in)) when both are right.
double kidnappedFitChi2(const KidnappedInput& in, const GaussianState& solution);
inline int kidnappedFitDof(const KidnappedInput& in) { return 2 * static_cast<int>(in.z_loc.size()) - 3; }

}  // namespace esif::dslam
