#pragma once
/// \file HeldFeatureTracking.h
/// First stage of D-SLAM's association without landmark IDs: the
/// measurements are associated (MRPT NN or JCBB, SearchBounds) with the
/// features the local SLAM holds, the features of the previous scan, using
/// the local SLAM's joint covariance of robot and features. Only what stays
/// unmatched goes on to the map-level association of Sec. 3.4.2
/// (RelativeAssociation), which takes the robot and the map as independent.
///
/// Why: after a stretch without features the robot is uncertain across its
/// path (1.7 m on configs/sim/long_gap.ini) and so is every feature mapped
/// since, but the two errors are almost the same error. Taken as independent
/// they make every feature within a few metres compatible with every
/// measurement, and on a grid whose spacing equals a distance between two
/// features in view the relative test (eq. 3.45) cannot tell them apart
/// either: the map-level association matched a measurement of the feature
/// seen a step before with one 4 m away, turned the robot by 25 deg, and
/// every later scan mapped its features again (long_gap: 441 features by
/// step 750, then a stall). The local SLAM holds exactly the correlation
/// that separates them.
///
/// The local SLAM holds features out of view too (local_hold_steps), and
/// after a blind drive its heading is uncertain by tens of degrees: on MRCLAM
/// robot 3 (dataset 6, step 224, heading sd 40 deg) JCBB matched a new pair of
/// cylinders to a held pair behind the robot and turned it by 2.1 rad. Only
/// the held features the predicted pose places in view are candidates, as in
/// the EKF. Widening that window by the robot's uncertainty, as the map-level
/// association does, let the same match through (MRCLAM median landmark RMSE
/// without IDs 1.02 m at 1 sigma, 1.82 m at 3, 0.68 m unwidened). A
/// measurement's min_distance2 still covers every held feature, so one near
/// a held feature out of view is left out as ambiguous, not mapped anew.

#include "LocalSlam.h"

#include <esif/association/CandidateWindow.h>
#include <esif/association/SearchBounds.h>
#include <esif/core/StepInput.h>

#include <optional>
#include <vector>

namespace esif::dslam
{
struct TrackedMeasurement
{
	std::optional<LandmarkId> feature;	///< the held feature it was associated with
	double min_distance2 = 0;			///< smallest squared Mahalanobis distance to any held feature
};

/// One entry per measurement of `scan`. `gate_quantile`: individual
/// compatibility chi-square confidence (2 dof); `jcbb`: JCBB rather than
/// nearest neighbour, within `bounds`. The candidates are the held features
/// `window` admits at their predicted range and bearing, as the EKF's are
/// (CandidateWindow.h), not widened by the robot's uncertainty.
std::vector<TrackedMeasurement> trackHeldFeatures(const LocalSlam& local, const Scan& scan, bool jcbb,
												  double gate_quantile, const CandidateWindow& window,
												  const SearchBounds& bounds);

}  // namespace esif::dslam
