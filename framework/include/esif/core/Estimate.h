#pragma once
/// \file Estimate.h
/// What a filter plugin reports: its estimate, its per-step data-association
/// decisions and its cost figures.

#include <esif/core/StepInput.h>

#include <mrpt/math/TPose2D.h>

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
	mrpt::math::TPose2D mean;
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
	/// Non-zeros of the information matrix; empty for covariance-form filters.
	std::optional<std::size_t> info_nnz;
	/// Further plugin-specific counters (name, value), e.g. reorderings.
	std::vector<std::pair<std::string, double>> counters;
};

}  // namespace esif
