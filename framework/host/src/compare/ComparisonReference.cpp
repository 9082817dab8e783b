#include "compare/ComparisonReference.h"

#include <esif/compare/BaselineComparison.h>
#include <esif/compare/ComparisonTable.h>
#include <esif/core/Errors.h>
#include <esif/eval/RunDifference.h>
#include <esif/formats/GroundTruth.h>
#include <esif/render/MapOverlay.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;

namespace esif
{
namespace
{
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
}  // namespace

ComparisonReference resolveReference(
	const std::string& reference, const std::vector<PlannedRun>& planned, const std::vector<std::string>& dirs)
{
	std::vector<std::string> labels, configs;
	for (const auto& p : planned)
	{
		labels.push_back(p.label);
		configs.push_back(p.config);
	}
	// A compared run's label or folder name first; else a run folder
	// outside, read (and so checked, a missing file named) before any run.
	const bool names_a_run =
		std::count(labels.begin(), labels.end(), reference) > 0 ||
		std::any_of(dirs.begin(), dirs.end(), [&](const std::string& d) { return fs::path(d).filename().string() == reference; });
	std::error_code ec;
	ComparisonReference out;
	if (!names_a_run && fs::is_directory(reference, ec))
		out.outside.emplace(reference, readReferenceRun(reference));
	else
		out.index = referenceIndex(reference, configs, labels, dirs);
	return out;
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
	if (!rawlog_input) return std::nullopt;
	if (reference) return reference;
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

}  // namespace esif
