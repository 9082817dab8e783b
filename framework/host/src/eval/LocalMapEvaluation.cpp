#include <esif/eval/LocalMapEvaluation.h>

namespace esif
{
std::optional<GroundTruth> localMapGroundTruth(const LocalMapFolder& folder)
{
	if (!folder.truth_landmarks && !folder.truth_end_poses) return std::nullopt;
	GroundTruth truth;
	if (folder.truth_landmarks) truth.landmarks = *folder.truth_landmarks;
	if (folder.truth_end_poses)
		for (const auto& [k, pose] : *folder.truth_end_poses) truth.path.push_back(pose);
	return truth;
}

std::optional<Accuracy> evaluateLocalMapRun(
	const LocalMapFolder& folder, const std::vector<TrajectoryPoint>& end_poses, const Estimate& estimate,
	const std::map<LandmarkId, LandmarkId>& filter_to_true)
{
	if (!folder.truth_landmarks && !folder.truth_end_poses) return std::nullopt;
	// evaluate() pairs trajectory point i with path row i: give it only the
	// end poses whose truth is known, renumbered 0, 1, ... in both.
	GroundTruth truth;
	if (folder.truth_landmarks) truth.landmarks = *folder.truth_landmarks;
	std::vector<TrajectoryPoint> paired;
	if (folder.truth_end_poses)
		for (const TrajectoryPoint& p : end_poses)
			if (const auto it = folder.truth_end_poses->find(p.step); it != folder.truth_end_poses->end())
			{
				paired.push_back({truth.path.size(), p.time_s, p.pose});
				truth.path.push_back(it->second);
			}
	return evaluate(truth, paired, estimate, filter_to_true);
}

}  // namespace esif
