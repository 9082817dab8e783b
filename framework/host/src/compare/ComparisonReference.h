#pragma once
/// \file ComparisonReference.h
/// What `esif compare` measures its runs against: the run --reference names
/// (a compared run's label or folder, or a run folder outside the
/// comparison), the optimization baseline by default without ground truth,
/// and the run every other one computes its whole-state NEES against.

#include <esif/compare/RunOrder.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/formats/StatsJson.h>
#include <esif/run/ConfigCheck.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace esif
{
/// The reference --reference names: a compared run (`index`) or a run
/// folder outside the comparison (`outside`, read and so checked now).
struct ComparisonReference
{
	std::optional<std::size_t> index;
	std::optional<std::pair<std::string, RunOutputs>> outside;
};

/// Resolves --reference `reference` among the planned runs and their run
/// folders `dirs`; ConfigError naming it when it names none or several.
ComparisonReference resolveReference(
	const std::string& reference, const std::vector<PlannedRun>& planned, const std::vector<std::string>& dirs);

/// The compared run every other run computes its whole-state NEES against
/// (--reference-run): the --reference run, else, on a rawlog without ground
/// truth, the full-SLAM baseline the runs are measured against (the first
/// full-SLAM config, as findBaseline picks it). Nullopt: each run's own
/// (against the ground truth, or none).
std::optional<std::size_t> wholeStateReference(
	const std::optional<std::size_t>& reference, const std::vector<CheckedConfig>& checked, bool rawlog_input,
	const std::string& ground_truth, const std::string& rawlog);

/// Filters are measured against the optimum: by accuracy ratios with
/// ground truth, else (unless --reference, given as index and label, says
/// otherwise) by their difference from it. Adds those keys to `runs` and
/// returns the notes, including a remark when the baseline's own check
/// finds its optimum implausible and one when the baseline's run failed.
std::string measureAgainstBaseline(
	std::vector<Stats>& runs, const std::vector<std::string>& dirs, const std::vector<CheckedConfig>& checked,
	const std::optional<std::pair<std::size_t, std::string>>& reference,
	const std::optional<std::pair<std::string, RunOutputs>>& outside_reference, const std::string& out_dir);

}  // namespace esif
