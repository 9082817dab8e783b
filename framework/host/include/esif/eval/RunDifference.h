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
/// Differences of a run from the reference. A statistic is nullopt when
/// there is nothing to compare (no common step, no matched landmark).
struct RunDifference
{
	/// Steps present in both trajectories (same timestamp) with finite poses in both.
	std::size_t steps_compared = 0;
	std::optional<double> trajectory_rms_m;	 ///< RMS of the position difference over those steps [m]
	std::optional<double> trajectory_max_m;	 ///< largest position difference [m]
	std::optional<double> heading_rms_deg;	///< RMS of the heading difference, wrapped to (-180, 180] [deg]

	/// Landmarks of the reference whose ID the run also has, both positions finite.
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
};

/// `run` against `reference`. Trajectory poses are paired by timestamp (both
/// runs replay the same rawlog, so the same steps have the same times),
/// landmarks by ID. Pairs where either side is not finite (a diverged
/// landmark written as nan) are left out of the statistics and the counts.
RunDifference runDifference(const RunOutputs& run, const RunOutputs& reference);

/// The reference's own row: zero differences where it has finite poses or
/// landmarks, and landmarks_matched = landmarks_in_reference (its own count).
RunDifference referenceItself(const RunOutputs& reference);

/// The stats keys written by setDifferenceStats, in table order:
/// ref_traj_rms_m, ref_traj_max_m, ref_heading_rms_deg, ref_landmark_rms_m,
/// ref_landmark_max_m, ref_landmarks_matched, ref_rotation_deg,
/// ref_landmark_rms_aligned_m, ref_landmarks_in_own95.
const std::vector<std::string>& runDifferenceKeys();

/// Adds the difference to a run's stats under runDifferenceKeys() (null for
/// a nullopt statistic), for comparison.csv and the comparison tables.
void setDifferenceStats(Stats& stats, const RunDifference& difference);

}  // namespace esif
