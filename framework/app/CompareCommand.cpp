#include <esif/safeio/ChildProcess.h>
#include "ConfigCheck.h"
#include "PluginPreload.h"
#include "CommandLine.h"
#include "Commands.h"

#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/core/Text.h>
#include <esif/compare/BaselineComparison.h>
#include <esif/compare/BookTable.h>
#include <esif/compare/ComparisonTable.h>
#include <esif/eval/RunDifference.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/Markdown.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/formats/StatsJson.h>
#include <esif/render/MapOverlay.h>
#include <esif/compare/ComparisonPage.h>
#include <esif/compare/RunOrder.h>
#include <esif/safeio/AtomicFile.h>
#include <esif/safeio/OutputApart.h>
#include <esif/safeio/RunFolder.h>
#include <esif/safeio/RunServer.h>
#include <esif/safeio/TerminationCleanup.h>

#include <cerrno>
#include <cstring>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace esif::app
{
namespace
{
std::string withoutTrailingSeparator(const std::string& dir)
{
	const fs::path p = fs::path(dir).lexically_normal();
	return (p.has_filename() ? p : p.parent_path()).string();
}

/// One output folder per config, named after the file (a suffix keeps repeats apart).
std::vector<std::string> runFolders(const std::vector<std::string>& configs, const std::string& out)
{
	std::vector<std::string> dirs;
	std::set<std::string> used;
	for (const auto& c : configs)
	{
		std::string name = fs::path(c).stem().string();
		for (int k = 2; used.count(name); ++k) name = fs::path(c).stem().string() + "_" + std::to_string(k);
		used.insert(name);
		dirs.push_back((fs::path(out) / name).string());
	}
	return dirs;
}

/// The label a config's run will carry: its [esif] label, else the config
/// file name (as the run pipeline sets it). Known before running, so that a
/// wrong --reference fails at once.
std::string configLabel(const ConfigFile& config)
{
	const std::string label = config.section("esif").getString("label", "");
	return label.empty() ? fs::path(config.origin()).stem().string() : label;
}

/// Index of the run `reference` names: the one run of that label, else the
/// run of that folder name. A label several runs carry names none of them,
/// even when one of their folders has that name too (which would be a
/// silent pick): refused, listing the folder names that pick one.
std::size_t referenceIndex(
	const std::string& reference, const std::vector<std::string>& configs, const std::vector<std::string>& labels,
	const std::vector<std::string>& dirs)
{
	std::vector<std::size_t> hits;
	for (std::size_t i = 0; i < labels.size(); ++i)
		if (labels[i] == reference) hits.push_back(i);
	if (hits.empty())
		for (std::size_t i = 0; i < dirs.size(); ++i)
			if (fs::path(dirs[i]).filename().string() == reference) hits.push_back(i);
	if (hits.size() == 1) return hits.front();
	std::string list;
	if (hits.empty())
	{
		for (const auto& l : labels) list += (list.empty() ? "" : ", ") + l;
		throw ConfigError(
			"esif compare: --reference '" + reference + "': not the label of a compared run (labels: " + list + ") nor a run folder");
	}
	std::string folders;
	for (const auto i : hits)
	{
		list += (list.empty() ? "" : ", ") + configs[i];
		const std::string folder = fs::path(dirs[i]).filename().string();
		if (std::find(labels.begin(), labels.end(), folder) == labels.end())
			folders += (folders.empty() ? "" : ", ") + folder;
	}
	throw ConfigError(
		"esif compare: --reference '" + reference + "': several runs have this label (" + list + "); " +
		(folders.empty() ? "" : "name one of their run folders (" + folders + ") or ") +
		"give each config its own [esif] label");
}

Stats readStats(const std::string& path)
{
	if (!fs::is_regular_file(path)) throw InputError(path + ": missing after the run");
	return Stats::load(path);
}

/// Every config parsed once, before any run: labels and associations_from
/// decide the reference and the run order, and a broken INI fails at once.
std::vector<PlannedRun> planRuns(const std::vector<std::string>& configs)
{
	std::vector<PlannedRun> planned;
	for (const auto& c : configs)
	{
		const ConfigFile config = ConfigFile::load(c);
		const auto host = config.section("esif");
		planned.push_back(
			{c, configLabel(config), host.getString("associations_from", "")});
	}
	return planned;
}

/// Shared settings of every `esif run` child.
struct ChildSettings
{
	std::string input_option;  ///< "--rawlog" or "--local-maps"
	std::string input;	///< the rawlog or the folder of local maps
	std::optional<std::string> ground_truth;
	std::optional<std::string> reference_result;
	std::optional<std::string> plugin_dir;
	/// With --reference on a rawlog: the reference's run folder, given to
	/// every other run as --reference-run so that it computes its
	/// whole-state NEES against it (state_nees*), as `esif run` does.
	std::optional<std::string> reference_run;
	/// The partial folder the runs write into and --out: a failed run's error
	/// line is shown with the folder it will have.
	std::pair<std::string, std::string> staging_to_out;
};

/// Runs one config as `esif run` into `dir`; `associations_dir` is the run
/// folder of the config its associations_from names, if any. Returns its
/// stats, or a failed row (failedRunStats) when the run failed.
Stats runConfig(
	const std::string& config, const CheckedConfig& checked, const std::string& label, const std::string& dir,
	const std::optional<std::string>& associations_dir, const ChildSettings& settings)
{
	std::vector<std::string> args = {"esif", "run", "--quiet", "--config", config, settings.input_option,
									 settings.input, "--out", dir};
	if (settings.ground_truth) args.insert(args.end(), {"--ground-truth", *settings.ground_truth});
	if (settings.reference_result) args.insert(args.end(), {"--reference-result", *settings.reference_result});
	if (settings.plugin_dir) args.insert(args.end(), {"--plugin-dir", *settings.plugin_dir});
	if (associations_dir) args.insert(args.end(), {"--associations-from", *associations_dir});
	if (settings.reference_run && *settings.reference_run != dir)
		args.insert(
			args.end(), {"--reference-run", *settings.reference_run, "--reference-run-name",
						 replaceAll(*settings.reference_run, settings.staging_to_out.first, settings.staging_to_out.second)});
	std::cerr << "esif compare: running " << config
			  << (associations_dir ? " (data association of " + *associations_dir + ")" : std::string()) << "\n";
	// Each config runs as its own `esif run` process; its stderr is passed on.
	const ChildResult child = runEsifChild(args, ChildOutput::Shown, "compare");
	if (child.exit_code != 0)
	{
		std::cerr << "esif compare: the run of " << config << " failed (exit " << child.exit_code
				  << "); the others go on\n";
		return failedRunStats(
			label, checked.plugin, child.exit_code,
			replaceAll(child.error_line, settings.staging_to_out.first, settings.staging_to_out.second));
	}
	try
	{
		return readStats((fs::path(dir) / "stats.json").string());
	}
	catch (const InputError& e)
	{
		// The run said it succeeded but left no readable stats: a failure all the same.
		return failedRunStats(label, checked.plugin, 1, e.what());
	}
}

std::string labelOf(const Stats& run) { return run.text("label").value_or("?"); }

/// Adds the ref_* keys (difference from `reference_outputs`: run `ref`'s,
/// or an outside run folder's when `ref` is none) to every run that did not
/// fail and draws their maps over the reference's into
/// OUT/maps_overlay.png; returns the note lines, which call the reference
/// `who` (e.g. "run 'ekf'"), or says that the reference failed.
std::string addReferenceColumns(std::vector<Stats>& runs, const std::vector<std::string>& dirs,
								const std::optional<std::size_t>& ref, const RunOutputs& reference_outputs,
								const std::string& reference_label, const std::string& who, const std::string& out_dir)
{
	std::vector<MapOverlayLayer> layers{{reference_label, reference_outputs}};
	for (std::size_t i = 0; i < runs.size(); ++i)
	{
		if (isFailedRun(runs[i])) continue;
		if (ref && i == *ref)
		{
			setDifferenceStats(runs[i], referenceItself(reference_outputs));
			continue;
		}
		RunOutputs outputs = readRunOutputs(dirs[i]);
		// The run's own OSPA cut-off (from the rawlog's measurements, so the
		// same for every run on it), else the reference run's.
		const auto cutoff = runs[i].number("ospa_c_m") ? runs[i].number("ospa_c_m")
													   : (ref ? runs[*ref].number("ospa_c_m") : std::nullopt);
		setDifferenceStats(runs[i], runDifference(outputs, reference_outputs, cutoff));
		layers.push_back({labelOf(runs[i]), std::move(outputs)});
	}
	writeMapOverlayImage(layers, "maps over " + who, (fs::path(out_dir) / "maps_overlay.png").string(), 1200);
	return "ref_*: difference from " + who +
		   " in the initial-pose frame, no alignment (trajectory by step; landmarks through their true landmarks, "
		   "or by the optimal assignment within the OSPA cut-off where a run has none: ref_landmarks_paired_by); "
		   "ref_ospa_m: OSPA of the two maps (p = 2, c = the run's ospa_c_m); ref_rotation_deg and "
		   "ref_landmark_rms_aligned_m: the best-fit rigid transform of the landmarks and what is left after it; "
		   "ref_landmarks_in_own95: share of landmarks whose reference position is inside the run's own 95% "
		   "ellipse; maps_overlay.png draws them\n";
}

/// The same against compared run `ref`.
std::string addReferenceColumns(std::vector<Stats>& runs, const std::vector<std::string>& dirs, std::size_t ref,
								const std::string& who, const std::string& out_dir)
{
	if (isFailedRun(runs[ref])) return "ref_*: none, " + who + " failed\n";
	RunOutputs reference;
	try
	{
		reference = readReferenceRun(dirs[ref]);
	}
	catch (const InputError& e)
	{
		return "ref_*: none, " + who + " is no reference: " + e.what() + "\n";
	}
	return addReferenceColumns(runs, dirs, ref, reference, labelOf(runs[ref]), who, out_dir);
}

/// A run folder outside the comparison is a reference only with a
/// trajectory row per step, as every compared run has (differences pair
/// rows by step: a shorter one would leave steps out silently).
void requireRowPerStep(
	const std::pair<std::string, RunOutputs>& reference, const std::vector<Stats>& runs,
	const std::vector<std::string>& dirs)
{
	for (std::size_t i = 0; i < runs.size(); ++i)
	{
		if (isFailedRun(runs[i])) continue;
		const std::size_t steps = readTrajectoryTum((fs::path(dirs[i]) / "trajectory.tum").string()).size();
		const std::size_t rows = reference.second.trajectory.size();
		if (rows != steps)
			throw InputError(
				(fs::path(reference.first) / "trajectory.tum").string() + ": " + std::to_string(rows) +
				" rows, the compared runs have " + std::to_string(steps) +
				" steps (a reference run must be of the same input, whole)");
		return;
	}
}

/// Every input of the comparison, for requireOutputApart: the configs, the
/// rawlog with its ground truth or the local-map folder, the reference
/// result and a reference run folder outside the comparison.
/// Empty strings stand for options not given.
std::vector<NamedInput> compareInputs(
	const std::vector<std::string>& configs, const std::string& rawlog, const std::string& local_maps,
	const std::string& ground_truth, const std::string& reference_result, const std::string& outside_reference)
{
	std::vector<NamedInput> inputs;
	for (const auto& c : configs) inputs.push_back({"the config", c});
	if (!rawlog.empty())
	{
		inputs.push_back({"the rawlog", rawlog});
		for (const auto& file : groundTruthFilesOf(ground_truth.empty() ? groundTruthPrefixFor(rawlog) : ground_truth))
			inputs.push_back({"the ground truth", file});
	}
	inputs.push_back({"the local-map folder", local_maps});
	inputs.push_back({"the reference result", reference_result});
	inputs.push_back({"the reference run", outside_reference});
	return inputs;
}

/// Runs every config in run order; a failed run is a row of its own and
/// the others still run, except those taking their data association from
/// it (rows "not run"). The runs after `reference` (wholeStateReference)
/// compute their whole-state NEES against it.
std::vector<Stats> runAll(
	const std::vector<std::string>& configs, const std::vector<CheckedConfig>& checked,
	const std::vector<PlannedRun>& planned, const std::vector<std::optional<std::size_t>>& sources,
	const std::vector<std::size_t>& order, const std::vector<std::string>& dirs, ChildSettings settings,
	const std::optional<std::size_t>& reference)
{
	std::vector<Stats> runs(configs.size());  // in the configs' order, whatever the run order
	for (const auto i : order)
	{
		const auto source = sources[i];
		if (source && isFailedRun(runs[*source]))
		{
			runs[i] = notRunStats(
				planned[i].label, checked[i].plugin,
				"its associations_from run '" + planned[*source].label + "' failed");
			continue;
		}
		runs[i] = runConfig(
			configs[i], checked[i], planned[i].label, dirs[i],
			source ? std::optional<std::string>(dirs[*source]) : std::nullopt, settings);
		// The runs after the reference (runOrder puts it first) are measured
		// against it; a failed reference leaves nothing to measure against.
		if (reference && i == *reference && !isFailedRun(runs[i]))
			settings.reference_run = dirs[i];
	}
	return runs;
}

/// When no run is the optimization baseline because the one that would
/// have been failed: says so (its plugin's formulation is known from the check).
std::string failedBaselineNote(const std::vector<Stats>& runs, const std::vector<CheckedConfig>& checked)
{
	for (std::size_t i = 0; i < runs.size(); ++i)
		if (isFailedRun(runs[i]) && checked[i].formulation == Formulation::FullSlamOptimum)
			return "no optimization baseline: the full-SLAM run '" + labelOf(runs[i]) +
				   "' failed, so no base_* ratios\n";
	return "";
}
/// The compared run every other run computes its whole-state NEES against
/// (--reference-run): the --reference run, else, on a rawlog without ground
/// truth, the full-SLAM baseline the runs are measured against (the first
/// full-SLAM config, as findBaseline picks it). Nullopt: each run's own
/// (against the ground truth, or none).
std::optional<std::size_t> wholeStateReference(
	const std::optional<std::size_t>& reference, const std::vector<CheckedConfig>& checked, bool rawlog_input,
	const std::string& ground_truth, const std::string& rawlog)
{
	if (reference || !rawlog_input) return rawlog_input ? reference : std::nullopt;
	const std::string prefix = ground_truth.empty() ? groundTruthPrefixFor(rawlog) : ground_truth;
	if (fs::exists(groundTruthFilesOf(prefix).front())) return std::nullopt;
	for (std::size_t i = 0; i < checked.size(); ++i)
		if (checked[i].formulation == Formulation::FullSlamOptimum) return i;
	return std::nullopt;
}

/// Filters are measured against the optimum: by accuracy ratios with
/// ground truth, else (unless --reference, given as index and label, says
/// otherwise) by their difference from it. Adds those keys to `runs` and
/// returns the notes, including a remark when the baseline's own check
/// finds its optimum implausible and one when the baseline's run failed.
std::string measureAgainstBaseline(
	std::vector<Stats>& runs, const std::vector<std::string>& dirs, const std::vector<CheckedConfig>& checked,
	const std::optional<std::pair<std::size_t, std::string>>& reference,
	const std::optional<std::pair<std::string, RunOutputs>>& outside_reference, const std::string& out_dir)
{
	std::string note;
	const BaselineChoice baseline = findBaseline(runs);
	if (baseline.warning) std::cerr << "esif: warning: " << *baseline.warning << "\n";
	const bool with_truth = hasGroundTruthFigures(runs);
	std::optional<std::string> implausible;
	if (baseline.index)
	{
		implausible = baselineImplausibility(runs[*baseline.index]);
		if (implausible) std::cerr << "esif: warning: " << *implausible << "\n";
		if (with_truth)
		{
			setBaselineRatios(runs, *baseline.index);
			note += baselineNote(labelOf(runs[*baseline.index]));
		}
	}
	else
		note += failedBaselineNote(runs, checked);
	if (outside_reference)
	{
		requireRowPerStep(*outside_reference, runs, dirs);
		note += addReferenceColumns(
			runs, dirs, std::nullopt, outside_reference->second, fs::path(outside_reference->first).filename().string(),
			"the run folder " + outside_reference->first, out_dir);
	}
	else if (reference)
		note += addReferenceColumns(runs, dirs, reference->first, "run '" + reference->second + "'", out_dir);
	else if (baseline.index && !with_truth)
	{
		note += addReferenceColumns(
			runs, dirs, *baseline.index, "the optimization baseline '" + labelOf(runs[*baseline.index]) + "'",
			out_dir);
	}
	// Only where something was measured against the baseline.
	if (implausible && (with_truth || !(reference || outside_reference))) note += *implausible + "\n";
	return note;
}
}  // namespace

int compareCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd("Runs several configs on one rawlog (or folder of local maps), each in its own process, and "
					   "tabulates them. Every config and its plugin is checked before the first run. A run that "
					   "fails is a row with status 'failed', its exit code and its first error line, the others "
					   "still run, the tables are written all the same, and compare exits with the code of the "
					   "first failed run in --configs order (0 when none failed).",
					   ' ',
					   ESIF_VERSION);
	TCLAP::ValueArg<std::string> configs("c", "configs", "comma-separated INI files", true, "", "A.ini,B.ini,...", cmd);
	TCLAP::ValueArg<std::string> rawlog("r", "rawlog", "MRPT rawlog (gz or plain); or give --local-maps", false, "",
										"FILE", cmd);
	TCLAP::ValueArg<std::string> local_maps(
		"", "local-maps",
		"folder of local maps (localmap_k.txt, ground truth beside them) instead of --rawlog; every config must "
		"name a local-map joining plugin",
		false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> reference_result(
		"", "reference-result",
		"with --local-maps: a joined result (feature.txt, pose.txt) every run is measured against (refres_* keys)",
		false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> ground_truth("g", "ground-truth", "ground-truth prefix; default: beside the rawlog",
											  false, "", "PREFIX", cmd);
	TCLAP::ValueArg<std::string> out("o", "out", "output folder (one subfolder per config)", true, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> plugin_dir("", "plugin-dir", "extra folder to search for plugins", false, "", "DIR",
											cmd);
	TCLAP::ValueArg<std::string> reference(
		"", "reference",
		"label of the run the others are compared with (for data without ground truth), or a run folder outside "
		"the comparison holding trajectory.tum and landmarks.txt (e.g. another solver's solution read by esif "
		"import g2o): adds each run's "
		"difference from it, in the shared initial-pose frame without alignment, as ref_traj_rms_m, "
		"ref_traj_max_m, ref_heading_rms_deg (poses of the same step), ref_landmark_rms_m, ref_landmark_max_m "
		"and ref_landmarks_matched (landmarks paired through the true landmark each stands for, or, where a run "
		"has none, by the optimal assignment within its OSPA cut-off: ref_landmarks_paired_by), ref_ospa_m. "
		"The reference's row shows zeros and its own landmark count. On a rawlog every other run also computes its "
		"whole-state NEES against the reference (state_nees*, as esif run --reference-run). Default without "
		"ground truth: the "
		"optimization baseline (the full-SLAM run), if any",
		false, "", "LABEL|DIR", cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;
	// Each config's run is a fork of the run server (RunServer.h), started
	// before this process opens a file or starts a thread, with the plugins
	// already loaded (PluginPreload.h).
	preloadPlugins(valueIfSet(plugin_dir));
	const RunServer server(runMain);
	if (rawlog.isSet() == local_maps.isSet())
		throw ConfigError("esif compare: give exactly one of --rawlog FILE and --local-maps DIR (see --help)");
	if (local_maps.isSet() && ground_truth.isSet())
		throw ConfigError("esif compare: --ground-truth applies to --rawlog input, not to --local-maps");
	if (rawlog.isSet() && reference_result.isSet())
		throw ConfigError("esif compare: --reference-result applies to --local-maps input, not to --rawlog");
	const std::optional<std::string> plugin_folder = valueIfSet(plugin_dir);

	const auto config_list = splitCommas(configs.getValue());
	if (config_list.empty()) throw ConfigError("esif compare: --configs: no config file given");
	for (const auto& c : config_list)	 // before planRuns reads them; checkConfigs below does the rest
		if (!fs::is_regular_file(c)) throw ConfigError(c + ": config file not found");
	const auto dirs = runFolders(config_list, out.getValue());
	const auto planned = planRuns(config_list);
	std::optional<std::size_t> ref;
	std::optional<std::pair<std::string, RunOutputs>> outside_reference;
	if (reference.isSet())
	{
		std::vector<std::string> labels;
		for (const auto& p : planned) labels.push_back(p.label);
		// A compared run's label or folder name first; else a run folder
		// outside, read (and so checked, a missing file named) before any run.
		const bool names_a_run =
			std::count(labels.begin(), labels.end(), reference.getValue()) > 0 ||
			std::any_of(dirs.begin(), dirs.end(),
						[&](const std::string& d) { return fs::path(d).filename().string() == reference.getValue(); });
		std::error_code ec;
		if (!names_a_run && fs::is_directory(reference.getValue(), ec))
			outside_reference.emplace(reference.getValue(), readReferenceRun(reference.getValue()));
		else
			ref = referenceIndex(reference.getValue(), config_list, labels, dirs);
	}
	const auto sources = associationSources(planned);
	runOrder(planned, sources);	 // a cycle fails here, before the configs are checked
	const auto checked = checkConfigs(config_list, plugin_folder, local_maps.isSet());
	const auto nees_reference =
		wholeStateReference(ref, checked, rawlog.isSet() && !outside_reference, ground_truth.getValue(), rawlog.getValue());
	const auto order = runOrder(planned, sources, nees_reference);
	requireOutputApart(
		out.getValue(), compareInputs(
							config_list, rawlog.getValue(), local_maps.getValue(), ground_truth.getValue(),
							reference_result.getValue(), outside_reference ? outside_reference->first : ""));

	// The comparison's folder is all-or-nothing like a run's; the runs are
	// written inside its partial folder.
	const auto [exit_code, text] = writeRunFolder(out.getValue(), {"comparison.csv", "comparison.md", "comparison.html"}, [&](const std::string& staging) {
		const auto run_dirs = runFolders(config_list, staging);
		const std::string input = rawlog.isSet() ? rawlog.getValue() : local_maps.getValue();
		const ChildSettings settings{
			rawlog.isSet() ? "--rawlog" : "--local-maps", input,
			valueIfSet(ground_truth), valueIfSet(reference_result),
			plugin_folder, outside_reference && rawlog.isSet() ? std::optional(outside_reference->first) : std::nullopt,
			{staging, withoutTrailingSeparator(out.getValue())}};
		std::vector<Stats> runs = runAll(config_list, checked, planned, sources, order, run_dirs, settings, nees_reference);
		markSucceededRuns(runs);

		std::string note = measureAgainstBaseline(
			runs, run_dirs, checked,
			ref ? std::optional<std::pair<std::size_t, std::string>>({*ref, reference.getValue()}) : std::nullopt,
			outside_reference, staging);
		if (reference_result.isSet())
			note += "refres_*: difference from the reference result " + reference_result.getValue() +
					" (landmarks by the files' feature IDs, end poses by map k, headings modulo 2 pi)\n";

		note += failureNote(runs);
		// Table 5.1 is about the estimators: failed runs have nothing to show there.
		std::vector<Stats> succeeded;
		for (const auto& run : runs)
			if (!isFailedRun(run)) succeeded.push_back(run);
		const std::string text = comparisonText(runs) + note + "\n" + bookTable51Text(succeeded);
		writeTextAtomically((fs::path(staging) / "comparison.csv").string(), comparisonCsv(runs));
		const std::string title = "esif compare on " + input;
		writeTextAtomically((fs::path(staging) / "comparison.md").string(),
							"# " + markdown::text(title) + "\n\n" + comparisonMarkdown(runs) +
								(note.empty() ? "" : "\n" + markdown::lines(note)) + "\n" +
								bookTable51Markdown(succeeded));
		writeComparisonPage((fs::path(staging) / "comparison.html").string(), {title, runs, run_dirs, note, staging});
		return std::make_pair(comparisonExitCode(runs), text);
	});
	std::cout << text;  // once the folder is in place
	return exit_code;
}

}  // namespace esif::app
