#pragma once
/// \file CandidateWindow.h
/// Which landmarks a scan could have seen: the association candidates. A
/// landmark is one when its predicted range and bearing fall within the
/// sensor's range and field of view plus margins, or when it lies within the
/// range margin whatever its bearing (the robot may drive over a feature,
/// and there the bearing says little). One rule for the EKF's association
/// (LandmarkEkf), D-SLAM's tracking of the features its local SLAM holds,
/// and D-SLAM's map-level association (RelativeAssociation), which widens it
/// by the robot's uncertainty.
///
/// Why a window at all, when the individual gate already weighs every
/// landmark: after a blind drive the heading is uncertain by tens of
/// degrees, and a scan of a pair of cylinders then fits any mapped pair
/// within that turn, behind the robot included; JCBB cannot tell equal
/// pairs apart. A landmark the predicted pose places out of view is far less
/// likely to be the one seen, which the Gaussian gate does not know.

#include <esif/core/StepInput.h>

#include <Eigen/Core>

namespace esif
{
class CandidateWindow
{
   public:
	/// The window of `scan`'s sensor (Scan::max_range_m, Scan::fov_rad; 0 =
	/// unlimited) widened by `margin_m` in range and `margin_deg` in bearing.
	CandidateWindow(const Scan& scan, double margin_m, double margin_deg);

	/// Whether a landmark predicted at `range_bearing` (sensor frame) is a
	/// candidate, with the window's range and bearing limits widened by
	/// `widen` ([m], [rad]; e.g. k standard deviations of the prediction,
	/// zero for the fixed window). The range margin's "near" rule is not
	/// widened.
	bool admits(const Eigen::Vector2d& range_bearing, const Eigen::Vector2d& widen = Eigen::Vector2d::Zero()) const;

   private:
	double max_range_m_;
	double half_fov_rad_;
	double near_m_;
};

}  // namespace esif
