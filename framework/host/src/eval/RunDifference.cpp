#include <esif/association/Chi2.h>
#include "eval/DifferenceSpread.h"
#include <esif/eval/LandmarkIdentities.h>
#include <esif/eval/LandmarkSetDistance.h>
#include <esif/eval/RunDifference.h>
#include <esif/models/Se2.h>

#include <mrpt/tfest/se2.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdio>
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

struct MatchedLandmark
{
	const LandmarkEstimate* run;
	const LandmarkEstimate* reference;
};

/// Each map's landmark that stands for a true landmark, paired through it,
/// finite on both sides, in the reference's order.
std::vector<MatchedLandmark> pairThroughTrueLandmarks(const RunOutputs& run, const RunOutputs& reference)
{
	std::unordered_map<LandmarkId, const LandmarkEstimate*> run_by_id;
	for (const auto& lm : run.landmarks) run_by_id.emplace(lm.id, &lm);
	// reference landmark -> the run's landmark for the same true landmark
	std::unordered_map<LandmarkId, LandmarkId> partner;
	const auto run_primary = primaryLandmarks(*run.identities);
	for (const auto& [true_id, ref_id] : primaryLandmarks(*reference.identities))
		if (const auto it = run_primary.find(true_id); it != run_primary.end()) partner.emplace(ref_id, it->second);
	std::vector<MatchedLandmark> matched;
	for (const auto& ref : reference.landmarks)
	{
		const auto it = partner.find(ref.id);
		if (it == partner.end()) continue;
		const LandmarkEstimate* lm = run_by_id.at(it->second);
		if (ref.mean.allFinite() && lm->mean.allFinite()) matched.push_back({lm, &ref});
	}
	return matched;
}

/// The pairs closer than c of the optimal assignment (the OSPA's), in the reference's order.
std::vector<MatchedLandmark> pairByAssignment(const SetMatch& match, const RunOutputs& run, const RunOutputs& reference)
{
	std::vector<std::pair<std::size_t, std::size_t>> by_reference;
	for (const auto& [i, j] : match.pairs) by_reference.emplace_back(j, i);
	std::sort(by_reference.begin(), by_reference.end());
	std::vector<MatchedLandmark> matched;
	for (const auto& [j, i] : by_reference) matched.push_back({&run.landmarks[i], &reference.landmarks[j]});
	return matched;
}

bool hasTrueLandmarks(const RunOutputs& run) { return run.identities && run.identities->truth; }

/// The rigid transform q with reference ~ q (+) run, by MRPT's closed-form
/// least squares; its rotation and the RMS left after applying it.
void fitRigidTransform(const std::vector<MatchedLandmark>& matched, RunDifference& out)
{
	mrpt::tfest::TMatchingPairList pairs;
	for (std::size_t i = 0; i < matched.size(); ++i)
	{
		const Eigen::Vector2d& g = matched[i].reference->mean;
		const Eigen::Vector2d& l = matched[i].run->mean;
		pairs.emplace_back(
			static_cast<uint32_t>(i), static_cast<uint32_t>(i), g.x(), g.y(), 0.0, l.x(), l.y(), 0.0);
	}
	mrpt::math::TPose2D q;
	if (!mrpt::tfest::se2_l2(pairs, q)) return;
	const double c = std::cos(q.phi), s = std::sin(q.phi);
	DifferenceSpread aligned;
	for (const auto& m : matched)
	{
		const Eigen::Vector2d& l = m.run->mean;
		const Eigen::Vector2d moved(q.x + c * l.x() - s * l.y(), q.y + s * l.x() + c * l.y());
		aligned.add((moved - m.reference->mean).norm());
	}
	out.best_fit_rotation_deg = wrapAngle(q.phi) * 180.0 / M_PI;
	out.landmark_rms_aligned_m = aligned.rms();
}

/// The share of landmarks whose reference position is inside the run's own
/// 95% ellipse; landmarks without a usable covariance are not counted.
void countInsideOwnEllipse(const std::vector<MatchedLandmark>& matched, RunDifference& out)
{
	static const double gate = chi2Quantile(0.95, 2);
	std::size_t usable = 0, inside = 0;
	for (const auto& m : matched)
	{
		const Eigen::Matrix2d& P = m.run->cov;
		if (!P.allFinite()) continue;
		const Eigen::LLT<Eigen::Matrix2d> llt(0.5 * (P + P.transpose()));
		if (llt.info() != Eigen::Success) continue;
		const Eigen::Vector2d d = m.reference->mean - m.run->mean;
		++usable;
		if (d.dot(llt.solve(d)) <= gate) ++inside;
	}
	out.landmarks_with_covariance = usable;
	if (usable) out.landmarks_inside_own95_fraction = static_cast<double>(inside) / static_cast<double>(usable);
}

/// The landmark pairs (see runDifference) and, with a cut-off, the OSPA of the maps.
std::vector<MatchedLandmark> pairLandmarks(
	const RunOutputs& run, const RunOutputs& reference, const std::optional<double>& cutoff_m, RunDifference& out)
{
	std::optional<SetMatch> match;
	if (cutoff_m)
	{
		match = matchPointSets(landmarkPositions(run.landmarks), landmarkPositions(reference.landmarks), *cutoff_m);
		out.cutoff_m = cutoff_m;
		out.ospa_m = match->ospa;
	}
	if (hasTrueLandmarks(run) && hasTrueLandmarks(reference))
	{
		out.pairing = LandmarkPairing::TrueLandmark;
		return pairThroughTrueLandmarks(run, reference);
	}
	if (!match) return {};
	out.pairing = LandmarkPairing::Assignment;
	return pairByAssignment(*match, run, reference);
}

/// Every finite landmark of `reference` paired with itself: its own row.
std::vector<MatchedLandmark> pairWithItself(const RunOutputs& reference)
{
	std::vector<MatchedLandmark> matched;
	for (const auto& lm : reference.landmarks)
		if (lm.mean.allFinite()) matched.push_back({&lm, &lm});
	return matched;
}

/// The landmark figures of `matched` pairs.
void compareLandmarks(const std::vector<MatchedLandmark>& matched, const RunOutputs& reference, RunDifference& out)
{
	DifferenceSpread position;
	for (const auto& m : matched) position.add((m.run->mean - m.reference->mean).norm());
	out.landmarks_in_reference = reference.landmarks.size();
	out.landmarks_matched = position.count();
	out.landmark_rms_m = position.rms();
	out.landmark_max_m = position.max();
	fitRigidTransform(matched, out);
	countInsideOwnEllipse(matched, out);
}
}  // namespace

std::string landmarkPairingText(LandmarkPairing pairing, const std::optional<double>& cutoff_m)
{
	switch (pairing)
	{
		case LandmarkPairing::TrueLandmark: return "true landmark";
		case LandmarkPairing::Assignment:
		{
			char c[32];
			std::snprintf(c, sizeof(c), "%.3g", cutoff_m.value_or(0));
			return std::string("assignment within c = ") + c + " m";
		}
		case LandmarkPairing::Itself: return "itself";
		case LandmarkPairing::None: break;
	}
	return "none";
}

RunDifference runDifference(const RunOutputs& run, const RunOutputs& reference, const std::optional<double>& cutoff_m)
{
	RunDifference out;
	compareTrajectories(run.trajectory, reference.trajectory, out);
	compareLandmarks(pairLandmarks(run, reference, cutoff_m, out), reference, out);
	return out;
}

RunDifference referenceItself(const RunOutputs& reference)
{
	RunDifference out;
	compareTrajectories(reference.trajectory, reference.trajectory, out);
	compareLandmarks(pairWithItself(reference), reference, out);
	out.landmarks_matched = out.landmarks_in_reference;
	out.pairing = LandmarkPairing::Itself;
	out.ospa_m = 0.0;
	return out;
}

const std::vector<std::string>& runDifferenceKeys()
{
	static const std::vector<std::string> keys = {
		"ref_traj_rms_m",		  "ref_traj_max_m",	  "ref_heading_rms_deg", "ref_landmark_rms_m",
		"ref_landmark_max_m",	  "ref_landmarks_matched", "ref_landmarks_paired_by", "ref_ospa_m",
		"ref_rotation_deg",		  "ref_landmark_rms_aligned_m", "ref_landmarks_in_own95"};
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
	stats.set(k[6], StatValue(landmarkPairingText(d.pairing, d.cutoff_m)));
	stats.set(k[7], d.ospa_m);
	stats.set(k[8], d.best_fit_rotation_deg);
	stats.set(k[9], d.landmark_rms_aligned_m);
	stats.set(k[10], d.landmarks_inside_own95_fraction);
}

}  // namespace esif
