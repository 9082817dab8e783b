#include <esif/eval/RunDifference.h>
#include <esif/eval/DifferenceSpread.h>
#include <esif/models/Se2.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace esif
{
namespace
{
bool isFinite(const mrpt::math::TPose2D& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.phi); }

/// Pairs the poses of equal timestamps (both trajectories have strictly
/// increasing times, see readTrajectoryTum) in one merge pass.
void compareTrajectories(
	const std::vector<TimedPose2D>& run, const std::vector<TimedPose2D>& reference, RunDifference& out)
{
	DifferenceSpread position, heading;
	for (std::size_t i = 0, j = 0; i < run.size() && j < reference.size();)
	{
		if (run[i].time_s < reference[j].time_s) ++i;
		else if (reference[j].time_s < run[i].time_s) ++j;
		else
		{
			const auto& a = run[i++].pose;
			const auto& b = reference[j++].pose;
			if (!isFinite(a) || !isFinite(b)) continue;
			position.add(std::hypot(a.x - b.x, a.y - b.y));
			heading.add(std::abs(wrapAngle(a.phi - b.phi)) * 180.0 / M_PI);
		}
	}
	out.steps_compared = position.count();
	out.trajectory_rms_m = position.rms();
	out.trajectory_max_m = position.max();
	out.heading_rms_deg = heading.rms();
}

void compareLandmarks(
	const std::vector<LandmarkEstimate>& run, const std::vector<LandmarkEstimate>& reference, RunDifference& out)
{
	std::unordered_map<LandmarkId, Eigen::Vector2d> in_run;
	for (const auto& lm : run) in_run.emplace(lm.id, lm.mean);
	DifferenceSpread position;
	for (const auto& ref : reference)
	{
		const auto it = in_run.find(ref.id);
		if (it == in_run.end() || !ref.mean.allFinite() || !it->second.allFinite()) continue;
		position.add((it->second - ref.mean).norm());
	}
	out.landmarks_in_reference = reference.size();
	out.landmarks_matched = position.count();
	out.landmark_rms_m = position.rms();
	out.landmark_max_m = position.max();
}
}  // namespace

RunDifference runDifference(const RunOutputs& run, const RunOutputs& reference)
{
	RunDifference out;
	compareTrajectories(run.trajectory, reference.trajectory, out);
	compareLandmarks(run.landmarks, reference.landmarks, out);
	return out;
}

RunDifference referenceItself(const RunOutputs& reference)
{
	RunDifference out = runDifference(reference, reference);
	out.landmarks_matched = out.landmarks_in_reference;
	return out;
}

const std::vector<std::string>& runDifferenceKeys()
{
	static const std::vector<std::string> keys = {"ref_traj_rms_m",		"ref_traj_max_m",	  "ref_heading_rms_deg",
												  "ref_landmark_rms_m", "ref_landmark_max_m", "ref_landmarks_matched"};
	return keys;
}

void setDifferenceStats(Stats& stats, const RunDifference& d)
{
	const auto& k = runDifferenceKeys();
	stats.set(k[0], d.trajectory_rms_m);
	stats.set(k[1], d.trajectory_max_m);
	stats.set(k[2], d.heading_rms_deg);
	stats.set(k[3], d.landmark_rms_m);
	stats.set(k[4], d.landmark_max_m);
	stats.set(k[5], StatValue(static_cast<long long>(d.landmarks_matched)));
}

}  // namespace esif
