#include "InitialGuess.h"

#include <esif/core/Errors.h>
#include <esif/formats/RunOutputReader.h>

#include <filesystem>

namespace esif::ceres_full
{
InitialGuess InitialGuess::load(const std::string& dir, const std::string& key)
{
	if (!std::filesystem::is_directory(dir)) throw InputError(key + ": " + dir + ": run folder not found");
	InitialGuess g;
	g.source_ = (std::filesystem::path(dir) / "trajectory.tum").string();
	try
	{
		const RunOutputs run = readRunOutputs(dir);
		for (const auto& p : run.trajectory) g.poses_.push_back(toPose2(p.pose));
		for (const auto& l : run.landmarks)
			if (l.mean.allFinite()) g.landmarks_.emplace(l.id, l.mean);
	}
	catch (const InputError& e)
	{
		throw InputError(key + ": " + e.what());
	}
	return g;
}

Pose2 InitialGuess::poseAfterStep(std::size_t k) const
{
	if (k >= poses_.size())
		throw InputError(
			source_ + ": has " + std::to_string(poses_.size()) + " poses, but the rawlog has more steps (is it the "
			"run of another rawlog?)");
	return poses_[k];
}

std::optional<Eigen::Vector2d> InitialGuess::landmark(LandmarkId id) const
{
	const auto it = landmarks_.find(id);
	if (it == landmarks_.end()) return std::nullopt;
	return it->second;
}

}  // namespace esif::ceres_full
