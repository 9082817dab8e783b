#pragma once
/// \file LocalMapConsistency.h
/// Where over-confidence enters a map-joining run: the consistency of each
/// local map on its own, against a reference (the truth, or a trusted run
/// such as the full-SLAM optimum) expressed in the map's start frame. A
/// local map is an EKF SLAM map started with zero uncertainty (eq. 4.2,
/// 5.1), so its end pose and features, relative to its start, are what it
/// claims to know; if those are inside their bounds and the joined map is
/// not, the fusion is at fault.

#include <esif/eval/StateNees.h>
#include <esif/localmap/LocalMap.h>

#include <map>
#include <optional>

namespace esif
{
struct LocalMapConsistency
{
	std::size_t index = 0;	///< k
	std::size_t features = 0;
	/// The whole map (end pose and every feature the reference has, the
	/// others marginalised) with its joint information.
	StateNees whole;
	/// The end pose alone (3 dof, its marginal covariance), and its heading
	/// error [rad] (estimate - reference, wrapped).
	double end_pose_nees = 0;
	double end_heading_error_rad = 0;
	/// Features with a reference, and the share inside their own 95% ellipse.
	std::size_t features_compared = 0;
	std::optional<double> features_inside_fraction;
};

/// The consistency of `map` against the reference: `start` and `end` the
/// reference poses of its start and end (frame of pose 0), `landmarks` the
/// reference positions by the map's feature IDs (frame of pose 0). Throws
/// NumericalError naming the map when its information is not positive
/// definite.
LocalMapConsistency localMapConsistency(
	const LocalMap& map, const Pose2& start, const Pose2& end, const std::map<LandmarkId, Eigen::Vector2d>& landmarks);

}  // namespace esif
