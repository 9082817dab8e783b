#pragma once
/// \file MonteCarloStatistics.h
/// Consistency and accuracy of one filter configuration over N Monte Carlo
/// runs of one scenario (independent noise draws): the average NEES (ANEES)
/// against its two-sided chi-square bounds (Bar-Shalom, Li, Kirubarajan,
/// "Estimation with Applications to Tracking and Navigation", 2001, Sec.
/// 5.4.2; Bailey et al., "Consistency of the EKF-SLAM algorithm", 2006).
///
/// Pose: at each step k, ANEES_k = (1/N_k) sum_r NEES_{r,k} over the N_k runs
/// with a NEES at k. For a consistent filter N_k ANEES_k ~ chi-square with
/// 3 N_k dof, so ANEES_k lies in [chi2inv(0.025, 3N_k), chi2inv(0.975, 3N_k)] / N_k
/// with probability 0.95.
///
/// Landmarks (final map): per landmark j, ANEES_j = mean over the N_j runs
/// that mapped j, with the 2 N_j-dof bounds. The campaign's landmark ANEES
/// is the mean of the NEES over all (run, landmark) pairs; it is held
/// against the same 2N-dof bounds of one landmark, not against 2 N M dof for
/// M landmarks: the landmarks of one run share the robot's error and are far
/// from independent, so M N pairs carry much less than 2 M N independent dof,
/// and the per-landmark bound is the honest (wider) one. The fraction of
/// landmarks whose own ANEES_j lies inside its bounds is reported beside it.

#include <esif/eval/EstimationErrors.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// Two-sided bounds of an ANEES.
struct AneesBounds
{
	double lo = 0;
	double hi = 0;
	bool contains(double anees) const { return anees >= lo && anees <= hi; }
};

/// [chi2inv((1-c)/2, dof N), chi2inv((1+c)/2, dof N)] / N for the average of
/// N independent NEES of `dof` degrees of freedom each (c = confidence, 0.95
/// by default). Boost.Math's chi-square quantile: exact at any dof (the gate
/// quantile of Chi2.h sums a series that overflows beyond ~1400 dof).
/// Throws std::invalid_argument for dof < 1 or runs < 1.
AneesBounds aneesBounds(int dof, std::size_t runs, double confidence = 0.95);

/// What one finished run contributes.
struct CampaignRunErrors
{
	std::size_t seed_index = 0;	 ///< which run of the campaign (for messages)
	std::vector<PoseError> poses;
	std::vector<LandmarkError> landmarks;
	double wall_s = 0;	///< the filter's replay time (stats.json wall_s)
	long long da_wrong = 0;	 ///< wrong associations (stats.json da_wrong)
	std::optional<std::string> suspect_reason;	///< stats.json suspect_reason of a suspect run
	/// The whole-state NEES and its dof (stats.json state_nees,
	/// state_nees_dof), when the back-end has an information matrix.
	std::optional<double> state_nees;
	std::size_t state_nees_dof = 0;
	/// The map's score (stats.json landmarks_true, landmarks_found,
	/// landmarks_duplicated, landmarks_spurious, da_precision, da_recall,
	/// landmark_ospa_m; AssociationScore.h, MapOspa.h), where the run has it.
	std::optional<double> landmarks_true, landmarks_found, landmarks_duplicated, landmarks_spurious;
	std::optional<double> da_precision, da_recall, landmark_ospa_m;
};

/// Mean and sample standard deviation (0 for one value).
struct MeanSpread
{
	double mean = 0;
	double stddev = 0;
};

/// Median and quartiles (linear interpolation between order statistics),
/// minimum and maximum.
struct Quantiles
{
	double median = 0, p25 = 0, p75 = 0, min = 0, max = 0;
};

struct StepStatistics
{
	std::size_t step = 0;
	std::size_t runs = 0;  ///< runs with a NEES at this step (N_k)
	std::optional<double> anees;  ///< none when no run has a NEES here (initial pose)
	AneesBounds bounds;	 ///< for N_k runs; zeros when runs = 0
	/// The same over the runs' position (2 dof) and heading (1 dof) NEES
	/// (PoseError), with their bounds for N_k runs; none when no run has one.
	std::optional<double> anees_position, anees_heading;
	AneesBounds bounds_position, bounds_heading;
	/// Over all runs reaching the step: sqrt(mean |e_xy|^2) [m] and
	/// sqrt(mean e_theta^2) [rad], and the 10th and 90th percentiles of |e_xy|.
	double position_rmse_m = 0;
	double heading_rmse_rad = 0;
	double position_error_p10_m = 0;
	double position_error_p90_m = 0;
};

struct LandmarkStatistics
{
	LandmarkId true_id = 0;
	std::size_t runs = 0;  ///< runs whose final map has it with a NEES (N_j)
	double anees = 0;
	AneesBounds bounds;	 ///< 2 N_j dof
	double rmse_m = 0;	///< over the runs that mapped it
};

struct ConfigStatistics
{
	std::string name;  ///< the config's name in the campaign
	std::size_t runs = 0;  ///< finished runs aggregated (N)
	std::vector<StepStatistics> steps;	///< by step
	std::vector<LandmarkStatistics> landmarks;	///< by ground-truth ID
	/// Mean of ANEES_k over the steps that have one, and the fraction of
	/// those steps with ANEES_k inside its bounds.
	std::optional<double> pose_anees_mean;
	std::optional<double> pose_steps_inside_fraction;
	AneesBounds pose_bounds;  ///< 3N dof: the bounds of a step all N runs reach
	/// Means over the steps of ANEES_k split into position (2 dof) and
	/// heading (1 dof): which part of the pose is over- or under-confident.
	std::optional<double> pose_position_anees_mean, pose_heading_anees_mean;
	std::optional<double> landmark_anees;  ///< mean NEES over all (run, landmark) pairs
	AneesBounds landmark_bounds;  ///< 2N dof (see the file comment)
	std::optional<double> landmarks_inside_fraction;  ///< of landmarks with ANEES_j inside their bounds
	/// Per run: position RMSE of the trajectory over its steps and RMSE of
	/// its final landmarks; mean and spread over runs.
	/// The whole-state test over the runs that have one (Sec. 5.6.1's, per
	/// run; StateNees.h): sum of NEES / sum of dof, whose 95% bounds are
	/// [chi2inv(0.025, D), chi2inv(0.975, D)] / D for D = sum of dof (each
	/// run is an independent draw, so the sum is chi-square(D) when every
	/// run is consistent); and the share of runs inside their own bounds.
	std::size_t state_runs = 0;
	std::optional<double> state_anees_per_dof;
	AneesBounds state_bounds;
	std::optional<double> state_runs_inside_fraction;
	MeanSpread trajectory_rmse_m;
	MeanSpread landmark_rmse_m;
	Quantiles wall_s;
	long long da_wrong_total = 0;
	std::size_t runs_with_da_wrong = 0;
	/// Over the runs that have them: medians of the true landmarks measured
	/// and of those found; duplicated and spurious landmarks summed, and in
	/// how many runs; precision and recall (median and lowest); the OSPA to
	/// the truth (mean and spread).
	std::optional<double> landmarks_true_median, landmarks_found_median;
	long long landmarks_duplicated_total = 0, landmarks_spurious_total = 0;
	std::size_t runs_with_duplicated = 0, runs_with_spurious = 0;
	std::optional<Quantiles> da_precision, da_recall;
	std::optional<MeanSpread> landmark_ospa_m;
};

/// The statistics of `runs` (at least one) of config `name`.
ConfigStatistics aggregateRuns(const std::string& name, const std::vector<CampaignRunErrors>& runs);

/// Quantiles of `values` (not empty).
Quantiles quantilesOf(std::vector<double> values);

/// Mean and sample standard deviation of `values` (not empty).
MeanSpread meanSpreadOf(const std::vector<double>& values);

}  // namespace esif
