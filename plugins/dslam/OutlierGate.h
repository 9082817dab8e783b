#pragma once
/// \file OutlierGate.h
/// Chi-square gates on D-SLAM's measurements, applied whatever the data
/// association (landmark IDs included), so a measurement that contradicts the
/// estimate is rejected instead of corrupting it:
/// - localisation: each measurement of a feature the local EKF SLAM holds,
///   by its range-bearing innovation against that EKF (individual
///   compatibility, 2 degrees of freedom);
/// - re-observation: each measurement of a mapped feature the local SLAM
///   does not hold (it left the view earlier), by its range-bearing
///   innovation against the map's estimate of the feature seen from the
///   local SLAM's robot. Without it, a misread ID of such a feature entered
///   the local SLAM unchecked (it is initialised from the measurement) and
///   reached the map through the chain's virtual observations;
/// - mapping: the measurements of mapped features in a scan, jointly, by the
///   innovation of their distances and angles (z_map, eq. 3.8) against the
///   map, S = dH P dH^T + R_map, as the book's association test, eq.
///   (3.43)-(3.45). While the joint test fails, the measurement whose
///   removal lowers the normalised distance most is rejected.

#include "LocalSlam.h"

#include <esif/relative/RelativeGeometry.h>

#include <vector>

namespace esif::dslam
{
/// Indices (into `scan`) of the measurements of features the local SLAM
/// holds whose innovation exceeds the chi-square(2) quantile `quantile`.
std::vector<int> localOutliers(const LocalSlam& local, const std::vector<IdentifiedMeasurement>& scan,
							   const Pose2& sensor_on_robot, double quantile);

/// Squared Mahalanobis distance of the range-bearing innovation of `m`, a
/// measurement of a mapped feature at `feature` (map covariance
/// `feature_cov`) seen from the local SLAM's robot `robot` (covariance
/// `robot_cov`): S = Hr Pr Hr^T + Hf Pf Hf^T + R, eq. (1.6) linearised. The
/// two estimates are taken as independent: the local SLAM holds the map's
/// information only through covariance intersection, which is conservative
/// for any correlation (Sec. 3.1.4.3).
double reobservationDistance2(const Pose2& robot, const Eigen::Matrix3d& robot_cov, const Pose2& sensor_on_robot,
							  const Eigen::Vector2d& feature, const Eigen::Matrix2d& feature_cov,
							  const IdentifiedMeasurement& m);

/// The measured points of the mapped features in view, with the map's
/// estimate of those features.
struct MappedView
{
	relative::PointSet measured;  ///< robot frame, joint covariance (dT1 R dT1^T)
	Eigen::VectorXd map_xy;		  ///< map positions, same order
	Eigen::MatrixXd map_cov;	  ///< their joint map covariance
};

/// Squared Mahalanobis distance of the z_map innovation of the points
/// `keep` (indices into the view, at least two; the first two are the
/// reference pair of the test) and its degrees of freedom.
std::pair<double, int> relativeDistance2(const MappedView& view, const std::vector<int>& keep);

/// Indices (into the view) rejected by the joint test at chi-square quantile
/// `quantile`, removed greedily; empty when the view passes as a whole. At
/// least two points always remain (two points have one relative
/// quantity, their distance; if that fails both are rejected).
std::vector<int> mappedOutliers(const MappedView& view, double quantile);

}  // namespace esif::dslam
