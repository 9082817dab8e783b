#include <esif/core/Errors.h>
#include <esif/plugin/InitialEstimate.h>

namespace esif
{
Pose2 InitialEstimate::poseAfterStep(std::size_t k) const
{
	if (k >= poses.size())
		throw InputError(
			source + ": has " + std::to_string(poses.size()) + " poses, but the rawlog has more steps (is it the "
			"run of another rawlog?)");
	return poses[k];
}

std::optional<Eigen::Vector2d> InitialEstimate::landmark(LandmarkId id) const
{
	const auto it = landmarks.find(id);
	if (it == landmarks.end()) return std::nullopt;
	return it->second;
}

}  // namespace esif
