#pragma once
/// \file Estimate.h
/// What a filter plugin reports: its estimate, its per-step data-association
/// decisions and its cost figures.

#include <esif/core/Pose2.h>
#include <esif/core/StepInput.h>

#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace esif
{
/// Robot pose with its 3x3 covariance over (x, y, phi).
struct PoseEstimate
{
	Pose2 mean = Pose2::Zero();  ///< (x [m], y [m], phi [rad]); (2) = heading
	Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
};

/// One mapped point feature.
struct LandmarkEstimate
{
	LandmarkId id = 0;
	Eigen::Vector2d mean = Eigen::Vector2d::Zero();
	Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
};

/// A filter's current estimate: robot pose and map.
struct Estimate
{
	PoseEstimate robot;
	std::vector<LandmarkEstimate> landmarks;
};

/// What the filter did with one measurement.
struct Association
{
	enum class Kind
	{
		New,  ///< started a new landmark `id`
		Matched,  ///< used to update existing landmark `id`
		Rejected  ///< not used (ambiguous or failed the gate)
	};
	Kind kind = Kind::Rejected;
	LandmarkId id = -1;	 ///< meaningful for New and Matched
};

/// Per-step report: one Association per measurement of the step's scan, in order.
struct StepReport
{
	std::vector<Association> associations;
};

/// Cost figures of a filter, for stats.json and comparison tables.
struct CostFigures
{
	std::size_t state_dim = 0;	///< dimension of the estimated state vector
	/// Robot poses in the state vector (book Table 5.1 "number of poses"):
	/// 1 for EKF SLAM, 0 for D-SLAM's map, every pose for full SLAM.
	std::size_t poses_in_state = 0;
	/// Non-zeros of the information matrix; empty for covariance-form filters.
	std::optional<std::size_t> info_nnz;
	/// Further plugin-specific counters (name, value), e.g. reorderings.
	std::vector<std::pair<std::string, double>> counters;
};

/// Which estimator of the book a plugin implements. The host and `esif
/// compare` use it to place a run in the book's tables (Table 5.1 columns)
/// and to find the optimization baseline every filter is measured against;
/// they never look at plugin names.
enum class Formulation
{
	Other,	///< none of the book's estimators
	EkfSlam,  ///< classical EKF SLAM (Sec. 1.2.1)
	FullSlamOptimum,  ///< MAP estimate over all poses and landmarks (Sec. 1.2.2.2): the baseline
	Dslam,	///< D-SLAM (Ch. 3)
	DslamLocalMapJoining,  ///< D-SLAM local map joining filter (Ch. 4)
	Slsjf  ///< sparse local submap joining filter (Ch. 5)
};

/// Stable name of a formulation for stats.json ("ekf_slam", "full_slam",
/// "dslam", "dslam_local_map_joining", "slsjf", "other").
const char* formulationName(Formulation f);

}  // namespace esif
