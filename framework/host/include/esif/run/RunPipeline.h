#pragma once
/// \file RunPipeline.h
/// One `esif run`: config -> plugin -> rawlog replay -> evaluation -> outputs.

#include <esif/formats/StatsJson.h>
#include <esif/loader/PluginLoader.h>

#include <optional>
#include <string>

namespace esif
{
struct RunRequest
{
	std::string config_path;
	std::string rawlog_path;
	/// Ground-truth prefix; when empty, PREFIX is looked for beside the rawlog.
	std::optional<std::string> ground_truth_prefix;
	std::string out_dir;
	bool progress_bar = true;
	/// Overrides `[esif] associations_from` (`esif run --associations-from`,
	/// which `esif compare` sets to the run folder of the config it names).
	std::optional<std::string> associations_from;
	/// A smoother's run folder (the full-SLAM optimum's) the whole-state NEES
	/// is computed against instead of the ground truth (`esif run
	/// --reference-run`; its trajectory.tum must hold one final pose per
	/// step), and the run's difference from it (the ref_* keys, RunDifference.h).
	std::optional<std::string> reference_run;
	/// How stats.json names the reference run (state_nees_reference);
	/// default: `reference_run` as given. `esif compare` gives the folder the
	/// reference will have once its comparison is in place.
	std::optional<std::string> reference_run_name;
	/// false: the data files only, no figure (`esif run --no-figures`; what
	/// `esif montecarlo` runs, whose summary draws the campaign's figures).
	bool figures = true;
};

/// Runs the whole pipeline and writes every output into request.out_dir:
/// map.simplemap, landmarks.gz, landmarks.txt, trajectory.tum, scene.3Dscene,
/// map.png, step_times.png, info_matrix.png (information-form plugins),
/// localmap_times.png (map-joining plugins that report fusion costs),
/// associations.txt (the plugin's decision for every measurement, see
/// AssociationFile.h), landmark_identities.txt (LandmarkIdentityFile.h),
/// stats.json and params.ini (the effective parameters).
/// Returns the stats. Warnings (e.g. a truncated rawlog) go to stderr.
/// The folder is all-or-nothing (RunFolder.h): locked while written, filled
/// aside and swapped into place only when complete, so a failure or a
/// signal leaves the previous folder (or none) as it was.
///
/// With `associations_from` (INI key or request override) set, the landmark
/// IDs of every measurement come from that folder's associations.txt before
/// the replay; a plugin that needs IDs is refused when none remain
/// (LandmarkIdRequirement.h). Config errors are found before any output is
/// written.
Stats runPipeline(const RunRequest& request, PluginLoader& loader);

}  // namespace esif
