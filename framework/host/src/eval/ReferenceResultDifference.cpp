#include "eval/DifferenceSpread.h"
#include <esif/eval/ReferenceResultDifference.h>
#include <esif/models/Se2.h>

#include <algorithm>
#include <cmath>

namespace esif
{
namespace
{
void compareLandmarks(
	const Estimate& estimate, const std::map<LandmarkId, LandmarkId>& filter_to_file, const ReferenceResult& reference,
	ReferenceResultDifference& out)
{
	DifferenceSpread position;
	for (const auto& lm : estimate.landmarks)
	{
		const auto file_id = filter_to_file.find(lm.id);
		if (file_id == filter_to_file.end()) continue;
		const auto ref = reference.features.find(file_id->second);
		if (ref == reference.features.end() || !lm.mean.allFinite() || !ref->second.allFinite()) continue;
		position.add((lm.mean - ref->second).norm());
	}
	out.landmarks_matched = position.count();
	out.landmark_rms_m = position.rms();
	out.landmark_max_m = position.max();
}

void comparePoses(
	const std::vector<TrajectoryPoint>& end_poses, const ReferenceResult& reference, ReferenceResultDifference& out)
{
	DifferenceSpread position, heading;
	for (const auto& p : end_poses)
	{
		const auto ref = reference.end_poses.find(p.step);
		if (ref == reference.end_poses.end()) continue;
		const Pose2 run = p.pose.mean;
		if (!run.allFinite() || !ref->second.allFinite()) continue;
		position.add((run.head<2>() - ref->second.head<2>()).norm());
		heading.add(std::abs(wrapAngle(run(2) - ref->second(2))) * 180.0 / M_PI);
	}
	out.poses_matched = position.count();
	out.pose_rms_m = position.rms();
	out.pose_max_m = position.max();
	out.heading_rms_deg = heading.rms();
}
}  // namespace

ReferenceResultDifference referenceResultDifference(
	const Estimate& estimate, const std::vector<TrajectoryPoint>& end_poses,
	const std::map<LandmarkId, LandmarkId>& filter_to_file, const ReferenceResult& reference)
{
	ReferenceResultDifference out;
	compareLandmarks(estimate, filter_to_file, reference, out);
	comparePoses(end_poses, reference, out);
	return out;
}

const std::vector<std::string>& referenceResultKeys()
{
	static const std::vector<std::string> keys = {
		"refres_landmark_rms_m", "refres_landmark_max_m",  "refres_landmarks_matched", "refres_pose_rms_m",
		"refres_pose_max_m",	 "refres_heading_rms_deg", "refres_poses_matched"};
	return keys;
}

void setReferenceResultStats(Stats& stats, const ReferenceResultDifference& d)
{
	const auto& k = referenceResultKeys();
	stats.set(k[0], d.landmark_rms_m);
	stats.set(k[1], d.landmark_max_m);
	stats.set(k[2], StatValue(static_cast<long long>(d.landmarks_matched)));
	stats.set(k[3], d.pose_rms_m);
	stats.set(k[4], d.pose_max_m);
	stats.set(k[5], d.heading_rms_deg);
	stats.set(k[6], StatValue(static_cast<long long>(d.poses_matched)));
}

}  // namespace esif
