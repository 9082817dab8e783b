#pragma once
/// \file RunDifference.h
/// How far one run's estimate is from another's (the reference), for real
/// data without ground truth (the book compares D-SLAM with EKF SLAM on
/// Victoria Park, Sec. 3.6.2). Both are in the frame of the initial robot
/// pose, which every run shares (relative SLAM, Sec. 1.3.1); the differences
/// fit no alignment, so a drift of one run is never hidden by a best-fit
/// transform. The best-fit rotation is reported beside them, to tell a map
/// that is only rotated (an EKF heading error) from one that is distorted.

#include <esif/formats/RunOutputReader.h>
#include <esif/formats/StatsJson.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// How a run's landmarks were paired with the reference's.
enum class LandmarkPairing
{
	/// Through their true landmarks (landmark_identities.txt on both sides):
	/// the landmark that stands for a true landmark in each map.
	TrueLandmark,
	/// Either side has no identities (no measurement carried its true
	/// landmark, or a folder without landmark_identities.txt): the optimal
	/// one-to-one assignment, pairs closer than the cut-off only.
	Assignment,
	/// The reference's own row.
	Itself,
	/// Neither: no identities and no cut-off (a run on local maps).
	None
};

/// "true landmark", "assignment within c = 0.43 m", "itself" or "none", for the table.
std::string landmarkPairingText(LandmarkPairing pairing, const std::optional<double>& cutoff_m);

/// Differences of a run from the reference. A statistic is nullopt when
/// there is nothing to compare (no common step, no matched landmark).
struct RunDifference
{
	/// Steps present in both trajectories (same timestamp) with finite poses in both.
	std::size_t steps_compared = 0;
	std::optional<double> trajectory_rms_m;	 ///< RMS of the position difference over those steps [m]
	std::optional<double> trajectory_max_m;	 ///< largest position difference [m]
	std::optional<double> heading_rms_deg;	///< RMS of the heading difference, wrapped to (-180, 180] [deg]

	/// Landmarks paired (see LandmarkPairing), both positions finite.
	std::size_t landmarks_matched = 0;
	std::size_t landmarks_in_reference = 0;	 ///< every landmark of the reference's map
	std::optional<double> landmark_rms_m;  ///< RMS of the matched landmarks' position difference [m]
	std::optional<double> landmark_max_m;  ///< largest matched landmark's position difference [m]

	/// Rotation of the least-squares rigid transform that moves the run's
	/// matched landmarks onto the reference's (MRPT tfest::se2_l2), wrapped
	/// to (-180, 180] [deg]; nullopt with fewer than two matched landmarks.
	std::optional<double> best_fit_rotation_deg;
	/// RMS landmark difference after that transform [m]: what is left once a
	/// rigid drift is taken out.
	std::optional<double> landmark_rms_aligned_m;
	/// Matched landmarks whose run covariance is usable (finite, positive
	/// definite), and the fraction of those whose reference position lies
	/// inside the run's own 95% ellipse (d^T P^-1 d <= chi2_2(0.95) = 5.991).
	/// A consistency test that needs no ground truth when the reference is
	/// the optimum: a consistent filter puts about 95% inside.
	std::size_t landmarks_with_covariance = 0;
	std::optional<double> landmarks_inside_own95_fraction;

	/// How the landmarks were paired (landmarkPairingText), and the OSPA of
	/// the two maps (order kOspaOrder, the run's cut-off; LandmarkSetDistance.h).
	LandmarkPairing pairing = LandmarkPairing::None;
	std::optional<double> cutoff_m;
	std::optional<double> ospa_m;
};

/// `run` against `reference`. Trajectory poses are paired by timestamp (both
/// runs replay the same rawlog, so the same steps have the same times),
/// landmarks through their true landmarks when both runs have identities,
/// else by the optimal assignment within `cutoff_m` (the run's OSPA cut-off,
/// MapOspa.h; no pairs without one): never by their numbers, which a filter
/// associating on its own chooses itself. Pairs where either side is not
/// finite (a diverged landmark written as nan) are left out of the
/// statistics and the counts.
RunDifference runDifference(
	const RunOutputs& run, const RunOutputs& reference, const std::optional<double>& cutoff_m);

/// The reference's own row: zero differences where it has finite poses or
/// landmarks, and landmarks_matched = landmarks_in_reference (its own count).
RunDifference referenceItself(const RunOutputs& reference);

/// The stats keys written by setDifferenceStats, in table order:
/// ref_traj_rms_m, ref_traj_max_m, ref_heading_rms_deg, ref_landmark_rms_m,
/// ref_landmark_max_m, ref_landmarks_matched, ref_landmarks_paired_by,
/// ref_ospa_m, ref_rotation_deg, ref_landmark_rms_aligned_m,
/// ref_landmarks_in_own95.
const std::vector<std::string>& runDifferenceKeys();

/// Adds the difference to a run's stats under runDifferenceKeys() (null for
/// a nullopt statistic), for comparison.csv and the comparison tables.
void setDifferenceStats(Stats& stats, const RunDifference& difference);

}  // namespace esif
