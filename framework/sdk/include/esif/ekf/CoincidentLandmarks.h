#pragma once
/// \file CoincidentLandmarks.h
/// Landmarks of an EKF associating without IDs that turn out to be one
/// point, merged after the fact.
///
/// Why: without IDs a sighting's landmark is chosen from the robot pose of
/// that moment. After a blind turn the pose is off by more than the 0.2 m
/// between MRCLAM's cylinders, so one cluster is mapped as several
/// landmarks, each taking the sightings nearest to it from a biased pose,
/// and the map settles off in one direction. Measured on MRCLAM dataset 6
/// (bench/mrclam_association_oracles.py): the EKF without IDs puts 100% of
/// the sightings it uses on a landmark of the right cluster, yet scores
/// 0.345 m, while one landmark per cluster on the same sightings scores
/// 0.194 m. Deciding the partition later, once the pose is known well,
/// is what the per-scan association cannot do.
///
/// Merging does it retroactively. Two landmarks whose estimates have
/// become statistically one point (the squared Mahalanobis distance of
/// their difference within the chi-square quantile `merge_chi2_quantile`,
/// 2 dof) are conditioned on being one (EkfSlamCore::mergeLandmarks), which
/// in the linear-Gaussian case gives exactly the posterior of having
/// associated all their sightings with one landmark from the start.
///
/// Two guards, each measured on MRCLAM without IDs (docs/plugins/ekf.md):
///  - Only landmarks each matched by distance at least
///    `merge_landmarks_after_matches` times take part. A landmark just
///    created from a sighting that failed every gate would otherwise be
///    merged at once (its covariance is still wide), which fuses exactly the
///    sighting the new-landmark test kept out.
///  - A merged landmark stands for the landmarks merged into it, and is
///    offered to the scan's association that many times (at most once per
///    measurement). The sensor resolves two cylinders of one cluster in
///    bearing when both are in view; with one candidate, a one-to-one
///    association (JCBB) gives the second sighting to a landmark of another
///    cluster rather than leave a pair out.
///
/// The merged-away landmark's ID is recorded, so that the reports of earlier
/// steps can name the landmark it became (finalId). A landmark whose ID the
/// sensor gave (a log whose scans carry IDs only at times) is never merged:
/// a later sighting with that ID must find it, and finalId must not send
/// the reports of a landmark re-created under it elsewhere.

#include <esif/core/Estimate.h>
#include <esif/ekf/EkfSlamCore.h>

#include <cstddef>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace esif
{
class CoincidentLandmarks
{
   public:
	/// `min_matches` 0 turns merging off.
	CoincidentLandmarks(int min_matches = 0, double chi2_quantile = 0.99);

	bool enabled() const { return min_matches_ > 0; }
	/// Counts a match by distance of landmark `id`.
	void countMatch(LandmarkId id) { ++matches_[id]; }
	/// Landmark `id` is named by the sensor: never merged.
	void keepApart(LandmarkId id) { named_by_sensor_.insert(id); }

	/// The pair of landmark indices (keep < drop) of `core` most likely one
	/// point among those eligible and within the gate, if any. `ids` gives
	/// each index's ID. O(N^2) pairs, each rejected in O(1) unless their
	/// distance is within reach of the gate.
	std::optional<std::pair<std::size_t, std::size_t>> nextPair(
		const EkfSlamCore& core, const std::vector<LandmarkId>& ids) const;

	/// Records that `dropped` was merged into `kept`.
	void recordMerge(LandmarkId kept, LandmarkId dropped);
	/// How many landmarks `id` stands for: 1 plus all merged into it.
	int standsFor(LandmarkId id) const;
	/// The landmark `id` is now part of (itself if never merged away).
	LandmarkId finalId(LandmarkId id) const;
	std::size_t merges() const { return merged_into_.size(); }

   private:
	bool eligible(LandmarkId id) const;

	int min_matches_ = 0;
	double gate_d2_ = 0;
	std::unordered_map<LandmarkId, int> matches_;
	std::unordered_map<LandmarkId, int> stands_for_;
	std::unordered_map<LandmarkId, LandmarkId> merged_into_;
	std::unordered_set<LandmarkId> named_by_sensor_;
};

}  // namespace esif
