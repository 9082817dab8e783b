/// \file ColumnMeanings.cpp
/// The rows of comparison.md and the columns of summary.md explained, and lookups; see ColumnMeanings.h.

#include <esif/eval/ColumnMeanings.h>

#include <algorithm>

namespace esif
{
const std::vector<ColumnMeaning>& comparisonColumnMeanings()
{
	static const std::vector<ColumnMeaning> meanings = {
		{{"plugin"}, "", "plugin class"},
		{{"status", "exit_code"},
		 "",
		 "only when a run failed or is suspect: `ok`, `suspect`, `failed` or `not run`; the failed run's exit code "
		 "(its first error line is in the CSV's `error` column and in the notes)"},
		{{"steps"}, "", "steps replayed (local maps: steps covered)"},
		{{"landmarks"}, "", "landmarks in the final map"},
		{{"state_dim"}, "", "state dimension"},
		{{"info_nnz"}, "", "non-zeros of the information matrix (`-` for covariance filters)"},
		{{"wall_s"}, "", "replay time [s]"},
		{{"step_us_mean", "step_us_p50", "step_us_p99", "step_us_max"}, "", "time per step [µs]"},
		{{"peak_rss_mb"}, "", "peak memory [MiB]"},
		{{"da_new", "da_matched", "da_rejected"}, "", "data-association decisions"},
		{{"da_wrong"}, "", "wrong associations against the rawlog's (or the simulator's true) IDs"},
		{{"landmarks_true", "landmarks_found", "landmarks_duplicated", "landmarks_spurious"},
		 "",
		 "with the true landmark of each measurement (the rawlog's IDs, shown or hidden, or the simulator's): the "
		 "true landmarks measured; those a landmark of the final map is identified with (the true landmark most of "
		 "its measurements came from); landmarks identified with a true landmark another landmark already stands "
		 "for (the one with most of its measurements); landmarks with no true landmark (clutter, or no measurement)"},
		{{"da_precision", "da_recall"},
		 "",
		 "the same: of the measurements used (new or matched), the share put on the landmark that stands for their "
		 "true landmark; of the measurements with a true landmark, the share so used (a rejected one counts against "
		 "recall, one put on a duplicate or on another true landmark's against both)"},
		{{"landmark_rmse_m", "ate_rmse_m"}, "", "ground truth: landmark and trajectory RMS error [m]"},
		{{"landmark_ospa_m", "ospa_c_m"},
		 "",
		 "ground truth: OSPA distance (p = 2) of the final map to the true landmarks measured, which needs no "
		 "identity; and its cut-off c, what one missing, extra or far landmark costs: 4.29 times the larger position "
		 "sigma of the median measurement (rawlog runs) [m]"},
		{{"landmark_nees_mean", "pose_nees_mean"},
		 "",
		 "ground truth: mean NEES of landmarks (2 dof) and poses (3 dof); about 2 and 3 for a consistent filter"},
		{{"landmark_consistent_fraction", "pose_consistent_fraction"},
		 "",
		 "ground truth: share inside the 95% bound; about 0.95 for a consistent filter"},
		{{"state_nees", "state_nees_dof", "state_nees_consistent"},
		 "information-form runs",
		 "the whole-state test of `stats.json`; consistent when inside the two-sided 95% interval of "
		 "chi-square(dof)"},
		{{"local_maps", "join_us_mean", "join_us_max"}, "map-joining runs", "local maps fused and time per fusion [µs]"},
		{{"base_landmark_rmse_ratio", "base_ate_ratio"},
		 "ground truth and a full-SLAM run in the comparison",
		 "the run's `landmark_rmse_m` and `ate_rmse_m` over the full-SLAM baseline's: 1 = as accurate as the optimum"},
		{{"ref_traj_rms_m", "ref_traj_max_m", "ref_heading_rms_deg"},
		 "a reference (below)",
		 "RMS and largest position difference and RMS heading difference from the reference's trajectory, same "
		 "steps of `trajectory.tum` [m, deg]"},
		{{"ref_landmark_rms_m", "ref_landmark_max_m", "ref_landmarks_matched"},
		 "a reference",
		 "RMS and largest difference of the landmarks paired with the reference's, and how many were paired (the "
		 "reference's own row: its landmark count)"},
		{{"ref_landmarks_paired_by", "ref_ospa_m"},
		 "a reference",
		 "how they were paired: through the true landmark each stands for (`landmark_identities.txt`), or, where "
		 "a run has none, by the optimal one-to-one assignment, pairs closer than c only; and the OSPA distance "
		 "(p = 2) of the two maps, with the run's c [m]"},
		{{"ref_rotation_deg", "ref_landmark_rms_aligned_m"},
		 "a reference",
		 "rotation of the best-fit rigid transform of the run's map onto the reference's (MRPT `tfest::se2_l2`) and "
		 "the RMS left after it: a map that is only rotated (an EKF heading error) against one that is distorted"},
		{{"ref_landmarks_in_own95"},
		 "a reference",
		 "share of landmarks whose reference position is inside the run's own 95% ellipse: a consistency test "
		 "without ground truth, about 0.95 for a consistent filter when the reference is the optimum"},
		{{"refres_landmark_rms_m", "refres_landmark_max_m", "refres_landmarks_matched", "refres_pose_rms_m",
		  "refres_pose_max_m", "refres_heading_rms_deg", "refres_poses_matched"},
		 "`--local-maps` with `--reference-result DIR`",
		 "difference from the reference result: landmarks by the files' feature IDs, end poses by map index k, "
		 "headings modulo 2 pi"},
	};
	return meanings;
}

const std::vector<ColumnMeaning>& monteCarloSummaryColumns()
{
	static const std::vector<ColumnMeaning> columns = {
		{{"config"}, "", "the config, by its file name"},
		{{"N"}, "", "runs aggregated: the config's finished runs"},
		{{"pose ANEES (mean over steps)"},
		 "",
		 "at each step the mean over runs of the pose NEES (3 dof), averaged over the steps"},
		{{"95% bounds (3N dof)"}, "", "the two-sided bounds [chi2inv(0.025, 3N), chi2inv(0.975, 3N)] / N"},
		{{"steps inside"}, "", "share of steps whose ANEES lies inside those bounds"},
		{{"position / heading ANEES"},
		 "",
		 "the same for the position (2 dof, ideal 2) and the heading (1 dof, ideal 1) alone: which part of the pose "
		 "is over- or under-confident (per step with bounds in `per_step.csv`)"},
		{{"landmark ANEES", "95% bounds (2N dof)"},
		 "",
		 "mean NEES (2 dof) of the final landmarks over all runs and landmarks, held against the bounds of one "
		 "landmark over N runs (one run's landmarks share its robot error, so they are not independent draws)"},
		{{"landmarks inside"}, "", "share of landmarks whose own ANEES over the runs that mapped them is inside its bounds"},
		{{"whole-state ANEES per dof", "95% bounds", "runs inside"},
		 "",
		 "back-ends with an information matrix: the book's whole-state test summed over the runs and divided by the "
		 "summed degrees of freedom D (ideal 1, bounds [chi2inv(0.025, D), chi2inv(0.975, D)] / D), and the share "
		 "of runs whose own NEES is inside its interval"},
		{{"trajectory RMSE [m]", "landmark RMSE [m]"},
		 "",
		 "per run, of the trajectory's positions over its steps and of its final landmarks; mean ± standard "
		 "deviation over runs"},
		{{"time per run [s]"}, "", "the filter's wall time per run, median [quartiles]"},
		{{"wrong associations"}, "", "`da_wrong` summed over runs, and in how many runs"},
		{{"true landmarks / found"}, "", "`landmarks_true` and `landmarks_found`, median over runs"},
		{{"duplicated / spurious"},
		 "",
		 "`landmarks_duplicated` and `landmarks_spurious` summed over runs, and in how many runs"},
		{{"precision / recall"}, "", "`da_precision` and `da_recall`, median over runs [lowest]"},
		{{"landmark OSPA [m]"},
		 "",
		 "`landmark_ospa_m` (p = 2, c = `ospa_c_m`, the same in every run of a scenario); mean ± standard deviation "
		 "over runs"},
	};
	return columns;
}

const ColumnMeaning* meaningOf(const std::vector<ColumnMeaning>& meanings, const std::string& column)
{
	for (const auto& m : meanings)
		if (std::find(m.columns.begin(), m.columns.end(), column) != m.columns.end()) return &m;
	return nullptr;
}

std::vector<const ColumnMeaning*> meaningsShown(
	const std::vector<ColumnMeaning>& meanings, const std::vector<std::string>& shown)
{
	std::vector<const ColumnMeaning*> out;
	for (const auto& m : meanings)
		if (std::any_of(m.columns.begin(), m.columns.end(), [&](const std::string& c) {
				return std::find(shown.begin(), shown.end(), c) != shown.end();
			}))
			out.push_back(&m);
	return out;
}

std::vector<std::string> columnHeadings(const std::vector<ColumnMeaning>& meanings)
{
	std::vector<std::string> out;
	for (const auto& m : meanings) out.insert(out.end(), m.columns.begin(), m.columns.end());
	return out;
}

std::string fullMeaning(const ColumnMeaning& m) { return m.when.empty() ? m.meaning : m.when + ": " + m.meaning; }

std::string plainMeaning(const ColumnMeaning& m)
{
	std::string text = fullMeaning(m);
	std::replace(text.begin(), text.end(), '`', '"');
	return text;
}

std::string columnList(const ColumnMeaning& m)
{
	std::string out;
	for (const auto& c : m.columns) out += (out.empty() ? "" : ", ") + c;
	return out;
}

}  // namespace esif
