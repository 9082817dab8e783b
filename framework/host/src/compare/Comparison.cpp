#include "compare/ComparisonReference.h"

#include <esif/compare/BookTable.h>
#include <esif/compare/Comparison.h>
#include <esif/compare/ComparisonPage.h>
#include <esif/compare/ComparisonTable.h>
#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/core/Text.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/Markdown.h>
#include <esif/safeio/AtomicFile.h>
#include <esif/safeio/ChildProcess.h>
#include <esif/safeio/OutputApart.h>
#include <esif/safeio/RunFolder.h>

#include <filesystem>
#include <iostream>
#include <set>

namespace fs = std::filesystem;

namespace esif
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
}  // namespace

Comparison::Comparison(ComparisonRequest request) : request_(std::move(request))
{
	if (request_.configs.empty()) throw ConfigError("esif compare: --configs: no config file given");
	for (const auto& c : request_.configs)	// before planRuns reads them; checkConfigs below does the rest
		if (!fs::is_regular_file(c)) throw ConfigError(c + ": config file not found");
	const auto dirs = runFolders(request_.configs, request_.out);
	planned_ = planRuns(request_.configs);
	if (!request_.reference.empty())
	{
		auto reference = resolveReference(request_.reference, planned_, dirs);
		reference_ = reference.index;
		outside_reference_ = std::move(reference.outside);
	}
	sources_ = associationSources(planned_);
	runOrder(planned_, sources_);  // a cycle fails here, before the configs are checked
	checked_ = checkConfigs(request_.configs, request_.plugin_dir, !request_.local_maps.empty());
	nees_reference_ = wholeStateReference(
		reference_, checked_, !request_.rawlog.empty() && !outside_reference_, request_.ground_truth, request_.rawlog);
	order_ = runOrder(planned_, sources_, nees_reference_);
	requireOutputApart(
		request_.out, compareInputs(
						  request_.configs, request_.rawlog, request_.local_maps, request_.ground_truth,
						  request_.reference_result, outside_reference_ ? outside_reference_->first : ""));
}

std::vector<Stats> Comparison::runAll(const std::vector<std::string>& dirs, const std::string& staging) const
{
	const auto optional = [](const std::string& s) { return s.empty() ? std::nullopt : std::optional(s); };
	ChildSettings settings{
		request_.rawlog.empty() ? "--local-maps" : "--rawlog", input(), optional(request_.ground_truth),
		optional(request_.reference_result), request_.plugin_dir,
		outside_reference_ && !request_.rawlog.empty() ? std::optional(outside_reference_->first) : std::nullopt,
		{staging, withoutTrailingSeparator(request_.out)}};
	std::vector<Stats> runs(request_.configs.size());  // in the configs' order, whatever the run order
	for (const auto i : order_)
	{
		const auto source = sources_[i];
		if (source && isFailedRun(runs[*source]))
		{
			runs[i] = notRunStats(
				planned_[i].label, checked_[i].plugin,
				"its associations_from run '" + planned_[*source].label + "' failed");
			continue;
		}
		runs[i] = runConfig(
			request_.configs[i], checked_[i], planned_[i].label, dirs[i],
			source ? std::optional<std::string>(dirs[*source]) : std::nullopt, settings);
		// The runs after the reference (runOrder puts it first) are measured
		// against it; a failed reference leaves nothing to measure against.
		if (nees_reference_ && i == *nees_reference_ && !isFailedRun(runs[i]))
			settings.reference_run = dirs[i];
	}
	return runs;
}

std::string Comparison::measure(
	std::vector<Stats>& runs, const std::vector<std::string>& dirs, const std::string& staging) const
{
	std::string note = measureAgainstBaseline(
		runs, dirs, checked_,
		reference_ ? std::optional<std::pair<std::size_t, std::string>>({*reference_, request_.reference}) : std::nullopt,
		outside_reference_, staging);
	if (!request_.reference_result.empty())
		note += "refres_*: difference from the reference result " + request_.reference_result +
				" (landmarks by the files' feature IDs, end poses by map k, headings modulo 2 pi)\n";
	return note + failureNote(runs);
}

std::string Comparison::writeTables(
	const std::vector<Stats>& runs, const std::string& note, const std::vector<std::string>& dirs,
	const std::string& staging) const
{
	// Table 5.1 is about the estimators: failed runs have nothing to show there.
	std::vector<Stats> succeeded;
	for (const auto& run : runs)
		if (!isFailedRun(run)) succeeded.push_back(run);
	writeTextAtomically((fs::path(staging) / "comparison.csv").string(), comparisonCsv(runs));
	const std::string title = "esif compare on " + input();
	writeTextAtomically(
		(fs::path(staging) / "comparison.md").string(),
		"# " + markdown::text(title) + "\n\n" + comparisonMarkdown(runs) +
			(note.empty() ? "" : "\n" + markdown::lines(note)) + "\n" + bookTable51Markdown(succeeded));
	writeComparisonPage(
		(fs::path(staging) / "comparison.html").string(),
		{title, runs, dirs, note, staging});
	return comparisonText(runs) + note + "\n" + bookTable51Text(succeeded);
}

std::pair<int, std::string> Comparison::run() const
{
	// The comparison's folder is all-or-nothing like a run's; the runs are
	// written inside its partial folder.
	return writeRunFolder(
		request_.out, {"comparison.csv", "comparison.md", "comparison.html"}, [&](const std::string& staging) {
			const auto dirs = runFolders(request_.configs, staging);
			std::vector<Stats> runs = runAll(dirs, staging);
			markSucceededRuns(runs);
			const std::string note = measure(runs, dirs, staging);
			return std::make_pair(comparisonExitCode(runs), writeTables(runs, note, dirs, staging));
		});
}

}  // namespace esif
