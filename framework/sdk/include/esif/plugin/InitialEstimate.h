#pragma once
/// \file InitialEstimate.h
/// Another run's estimate, handed by the host to a plugin that starts from
/// one (`[esif] initial_run`, FilterPlugin::setInitialEstimate): the host
/// reads the run folder, so a plugin reads no files.

#include <esif/core/StepInput.h>
#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace esif
{
struct InitialEstimate
{
	std::string source;	 ///< where it was read from (the run folder), for error messages
	std::vector<Pose2> poses;  ///< the run's pose after step k (index k)
	std::unordered_map<LandmarkId, Eigen::Vector2d> landmarks;	///< its finite landmark positions

	/// The pose after step k; InputError naming `source` when the run has
	/// fewer poses (the host checks the length before the replay).
	Pose2 poseAfterStep(std::size_t k) const;
	/// The position of landmark `id`, if the run mapped it.
	std::optional<Eigen::Vector2d> landmark(LandmarkId id) const;
};

}  // namespace esif
