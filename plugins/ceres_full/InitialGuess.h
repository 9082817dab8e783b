#pragma once
/// \file InitialGuess.h
/// Another run's estimate as the starting point of the optimization (e.g. a
/// filter's map on data where dead reckoning is far from the optimum).

#include <esif/core/StepInput.h>
#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace esif::ceres_full
{
class InitialGuess
{
   public:
	/// Reads DIR/trajectory.tum (one pose per step) and DIR/landmarks.txt.
	/// Throws InputError naming `key` and the file.
	static InitialGuess load(const std::string& dir, const std::string& key);

	/// The run's pose after step k; InputError when its trajectory is shorter.
	Pose2 poseAfterStep(std::size_t k) const;
	/// The run's position of landmark `id`, if it mapped it (finite).
	std::optional<Eigen::Vector2d> landmark(LandmarkId id) const;

   private:
	std::string source_;
	std::vector<Pose2> poses_;
	std::unordered_map<LandmarkId, Eigen::Vector2d> landmarks_;
};

}  // namespace esif::ceres_full
