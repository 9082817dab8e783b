#pragma once
/// \file StateInformation.h
/// The whole state of an information-form back-end with its information
/// matrix, for the book's consistency test of the whole estimate (the
/// chi-square of all features and poses at once, eval/StateNees.h): what a
/// plugin reports through FilterPlugin::stateInformation().

#include <esif/core/StepInput.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstddef>
#include <optional>
#include <vector>

namespace esif
{
/// One variable of the state vector, in the order of the vector.
struct StateVariable
{
	enum class Kind
	{
		Landmark,  ///< 2 scalars: x, y [m]
		Pose  ///< 3 scalars: x, y [m], phi [rad]
	};
	Kind kind = Kind::Landmark;
	LandmarkId landmark = 0;  ///< Landmark: its ID (as in the plugin's estimate())
	/// Pose: the rawlog step after which the robot stood there; nullopt when
	/// the pose belongs to no step (a pose of local-map input, see local_map).
	std::optional<std::size_t> step;
	/// Pose: the local map whose end pose it is (k), for the map-joining
	/// filters; nullopt otherwise.
	std::optional<std::size_t> local_map;

	int dim() const { return kind == Kind::Landmark ? 2 : 3; }
	static StateVariable landmarkOf(LandmarkId id) { return {Kind::Landmark, id, std::nullopt, std::nullopt}; }
	static StateVariable poseOf(std::optional<std::size_t> step, std::optional<std::size_t> local_map = std::nullopt)
	{
		return {Kind::Pose, 0, step, local_map};
	}
};

/// The estimate x (stacked in the order of `variables`) and the information
/// matrix I of the Gaussian N(x, I^-1) the back-end holds.
struct StateInformation
{
	std::vector<StateVariable> variables;
	Eigen::VectorXd mean;
	Eigen::SparseMatrix<double> information;  ///< symmetric, both triangles stored
};

}  // namespace esif
