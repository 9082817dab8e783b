#pragma once
/// \file Comparison.h
/// `esif compare`: several configs on one rawlog (or folder of local maps),
/// each run as its own `esif run` child, then tabulated side by side with
/// the optimization baseline and a reference. Everything that can be wrong
/// with the request (a config, a plugin, the reference, the run order, an
/// output among the inputs) is found when the comparison is planned,
/// before any run has cost time or any folder exists.

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
struct ComparisonRequest
{
	std::vector<std::string> configs;  ///< INI files, in table order
	std::string rawlog;	 ///< the input: a rawlog ...
	std::string local_maps;	 ///< ... or a folder of local maps (exactly one is set)
	std::string ground_truth;  ///< ground-truth prefix; empty = beside the rawlog
	std::string reference_result;  ///< with local maps: a joined result (refres_*); empty = none
	std::string reference;	///< --reference: a run's label or folder, or a run folder outside; empty = none
	std::string out;  ///< the comparison's folder
	std::optional<std::string> plugin_dir;	///< an extra plugin folder
};

class Comparison
{
   public:
	/// Plans the comparison; throws ConfigError or InputError naming what is wrong.
	explicit Comparison(ComparisonRequest request);

	/// Runs every config into the comparison's folder (all-or-nothing, like
	/// a run's) and writes comparison.csv, .md and .html. Returns the exit
	/// code (that of the first failed run in config order, 0 when none
	/// failed) and the text to print once the folder is in place.
	std::pair<int, std::string> run() const;

   private:
	std::string input() const { return request_.rawlog.empty() ? request_.local_maps : request_.rawlog; }
	/// Every run, into its folder of `dirs` (inside `staging`), in run order.
	std::vector<Stats> runAll(const std::vector<std::string>& dirs, const std::string& staging) const;
	/// The notes under the tables: baseline, reference, failures.
	std::string measure(std::vector<Stats>& runs, const std::vector<std::string>& dirs, const std::string& staging) const;
	/// Writes the three tables into `staging`; returns the printed text.
	std::string writeTables(
		const std::vector<Stats>& runs, const std::string& note, const std::vector<std::string>& dirs,
		const std::string& staging) const;

	ComparisonRequest request_;
	std::vector<PlannedRun> planned_;
	std::vector<std::optional<std::size_t>> sources_;  ///< associations_from sources (RunOrder.h)
	std::vector<CheckedConfig> checked_;
	std::optional<std::size_t> reference_;	///< a compared run named by --reference
	std::optional<std::pair<std::string, RunOutputs>> outside_reference_;
	std::optional<std::size_t> nees_reference_;	 ///< the run others compute their whole-state NEES against
	std::vector<std::size_t> order_;
};

}  // namespace esif
