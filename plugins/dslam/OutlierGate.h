#pragma once
/// \file OutlierGate.h
/// Chi-square gates on D-SLAM's measurements, applied whatever the data
/// association (landmark IDs included), so a measurement that contradicts the
/// estimate is rejected instead of corrupting it:
/// - localisation: each measurement of a feature the local EKF SLAM holds,
///   by its range-bearing innovation against that EKF (individual
///   compatibility, 2 degrees of freedom);
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
