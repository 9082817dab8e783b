#pragma once
/// \file MonteCarloCampaign.h
/// The folder of a Monte Carlo campaign (`esif montecarlo`) and what is in
/// it. One campaign is one scenario, simulated once per noise seed (new
/// noise on the same world and path: [simulation] noise_seed), and every
/// config replayed on each simulation. Layout of DIR:
///   campaign.ini                       scenario, configs, first noise seed, runs
///   sim/seed_<S>/sim.rawlog            one simulation per noise seed S (+ ground truth)
///   runs/<config>/seed_<S>/            one `esif run` folder per config and seed
///   failures/<config>/seed_<S>.txt     why a run failed (exit code, first error line, stderr)
///   summary.csv, summary.md, summary.html, per_step.csv, landmarks.csv, *.png: the aggregate
/// A finished run is a run folder with stats.json (run folders are
/// all-or-nothing, RunFolder.h), a simulation a sim/seed_<S> folder (put in
/// place by one rename): re-running a campaign skips both.

#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// Largest number of noise draws of one campaign (--runs, campaign.ini
/// `runs`): 100,000 runs of one config take days on a cluster; beyond is a typo.
inline constexpr int kMaxCampaignRuns = 100000;

/// Whether `name` may name a config's folders under runs/ and failures/:
/// letters, digits, '_', '-', '+' and '.', not starting with '.', at most
/// 100 characters, so no name reaches outside the campaign folder.
bool isCampaignName(const std::string& name);

struct CampaignPlan
{
	std::string scenario;  ///< absolute path of the scenario INI
	std::vector<std::string> configs;  ///< absolute paths of the filter configs
	std::vector<std::string> names;	 ///< each config's folder name under runs/ (its file name, made safe and unique)
	int seed0 = 1;	///< noise seed of the first run
	int runs = 0;  ///< noise seeds seed0 .. seed0 + runs - 1

	/// The plan of a new campaign: paths made absolute, names from the file
	/// names (a suffix _2, _3 keeps repeats apart).
	static CampaignPlan create(
		const std::string& scenario, const std::vector<std::string>& configs, int seed0, int runs);

	/// The plan in DIR/campaign.ini; InputError naming the file when it is
	/// missing or malformed: runs outside [1, kMaxCampaignRuns], seeds beyond
	/// INT_MAX, a name that fails isCampaignName or is given twice.
	static CampaignPlan load(const std::string& dir);

	/// `requested` merged into this existing plan: the same scenario and
	/// first seed are required (ConfigError naming campaign.ini otherwise),
	/// configs not yet in it are added, and the larger number of runs is kept.
	CampaignPlan mergedWith(const CampaignPlan& requested, const std::string& dir) const;

	/// campaign.ini's text.
	std::string iniText() const;

	/// Index of the config named `name`; nullopt when none is.
	std::optional<std::size_t> configIndex(const std::string& name) const;
};

/// One run of the campaign: config `config` on the simulation of `noise_seed`.
struct CampaignJob
{
	std::size_t config = 0;
	int noise_seed = 0;
};

/// Every run of `plan`, seed by seed (all configs of the first seed first),
/// so that a seed's simulation is shared by runs that start close together.
std::vector<CampaignJob> campaignJobs(const CampaignPlan& plan);

/// The paths of the campaign in `dir`.
namespace campaign_layout
{
std::string manifest(const std::string& dir);
std::string seedName(int noise_seed);  ///< "seed_0007"
std::string simFolder(const std::string& dir, int noise_seed);
std::string simRawlog(const std::string& dir, int noise_seed);
std::string runFolder(const std::string& dir, const std::string& name, int noise_seed);
std::string failureFile(const std::string& dir, const std::string& name, int noise_seed);
/// "ekf/seed_0007": how a job is named on the command line (--job).
std::string jobId(const CampaignPlan& plan, const CampaignJob& job);
/// The job `id` names; ConfigError naming it when it is not of the form
/// <config name>/seed_<S> with a config of the plan and S in its seeds.
CampaignJob parseJobId(const CampaignPlan& plan, const std::string& id);
}  // namespace campaign_layout

/// Throws InputError naming the first symbolic link found under the
/// campaign folder `dir` (links are not followed): a run, simulation or
/// failure record written through one would land outside --out, and a run
/// read through one would be another folder's.
void requireNoLinksInCampaign(const std::string& dir);

enum class JobState
{
	Finished,  ///< run folder with stats.json
	Failed,	 ///< a failure record and no finished run
	Pending	 ///< neither: not run yet, running, or killed
};

JobState jobState(const std::string& dir, const CampaignPlan& plan, const CampaignJob& job);

/// Why a run failed, as recorded in failures/<config>/seed_<S>.txt.
struct FailureRecord
{
	int exit_code = 0;
	std::string error_line;
	std::string stderr_text;  ///< everything the failed step wrote to stderr
};

/// Writes the record atomically (its folder is created).
void writeFailureRecord(const std::string& path, const FailureRecord& record);
/// Reads a record; InputError naming the file when malformed.
FailureRecord readFailureRecord(const std::string& path);

}  // namespace esif
