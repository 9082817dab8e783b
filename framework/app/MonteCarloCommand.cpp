/// \file MonteCarloCommand.cpp
/// `esif montecarlo`: a Monte Carlo campaign of one scenario and several
/// configs (MonteCarloCampaign.h), run on local cores, or emitted as a job
/// list for GNU parallel, xargs -P or a Slurm array, and aggregated
/// (MonteCarloCollect.h).

#include "CommandLine.h"
#include "Commands.h"
#include <esif/run/ConfigCheck.h>
#include "PluginPreload.h"
#include <esif/montecarlo/MonteCarloJobs.h>

#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/montecarlo/MonteCarloCollect.h>
#include <esif/safeio/AtomicFile.h>
#include <esif/safeio/FileSet.h>
#include <esif/safeio/FolderLock.h>
#include <esif/safeio/OutputApart.h>
#include <esif/safeio/RunServer.h>
#include <esif/sim/Scenario.h>

#include <climits>
#include <filesystem>
#include <iostream>
#include <optional>
#include <thread>

namespace fs = std::filesystem;

namespace esif::app
{
namespace
{
/// The scenario loads and passes its cross-key rules, as `esif simulate` checks it.
void checkScenario(const std::string& path)
{
	if (!fs::is_regular_file(path)) throw ConfigError(path + ": scenario file not found");
	const Scenario scenario = Scenario::fromConfig(ConfigFile::load(path));
	try
	{
		scenario.validate();
	}
	catch (const ConfigError& e)
	{
		throw ConfigError(path + ": " + e.what());
	}
}

/// The campaign's plan after merging the request into what DIR holds; a
/// folder that is neither empty nor a campaign is refused.
CampaignPlan planCampaign(const std::string& dir, const CampaignPlan& requested)
{
	std::error_code ec;
	if (fs::is_regular_file(campaign_layout::manifest(dir), ec))
		return CampaignPlan::load(dir).mergedWith(requested, dir);
	if (fs::exists(dir, ec) && !(fs::is_directory(dir, ec) && fs::is_empty(dir, ec)))
		throw InputError(dir + ": exists and is not a campaign folder (no campaign.ini): choose another --out");
	return requested;
}

std::vector<CampaignJob> unfinishedJobs(const std::string& dir, const CampaignPlan& plan)
{
	std::vector<CampaignJob> jobs;
	for (const auto& job : campaignJobs(plan))
		if (inspectJob(dir, plan, job).state != JobState::Finished) jobs.push_back(job);
	return jobs;
}

/// Aggregates what `dir` holds, writes the outputs and prints the summary.
void collectAndReport(const std::string& dir, const CampaignPlan& plan)
{
	const CampaignCollection c = collectCampaign(dir, plan);
	if (c.configs.empty())
		throw InputError(
			dir + ": no finished run to aggregate (" + std::to_string(c.gaps.failed.size()) + " failed, " +
			std::to_string(c.gaps.pending.size()) + " not finished)");
	std::cout << writeCampaignOutputs(dir, plan, c);
	std::cout << "\nesif montecarlo: " << c.finished << " of " << c.total << " runs finished ("
			  << c.gaps.suspect.size() << " suspect), " << c.gaps.failed.size() << " failed, "
			  << c.gaps.pending.size() << " not finished; outputs in " << dir
			  << " (summary.md, summary.html, summary.csv, per_step.csv, landmarks.csv, anees_pose.png, rmse.png, "
				 "landmark_anees.png)\n";
}

int runOneJob(const std::string& dir, const std::string& id)
{
	requireNoLinksInCampaign(dir);
	const CampaignPlan plan = CampaignPlan::load(dir);
	const JobOutcome outcome = runCampaignJob(dir, plan, campaign_layout::parseJobId(plan, id));
	if (outcome.exit_code != 0)
		std::cerr << "esif montecarlo: " << outcome.id << " failed (exit " << outcome.exit_code
				  << "): " << outcome.error_line << "\n";
	else if (outcome.skipped && !outcome.error_line.empty())
		std::cerr << "esif montecarlo: " << outcome.id << ": " << outcome.error_line << ", left to it\n";
	return outcome.exit_code;
}

/// One campaign at a time on a folder: a second would record the first
/// one's runs as its own failures. (Jobs of a job list take no such lock:
/// they run side by side, each job under a lock of its own.) The lock file
/// is beside the folder, whose parent is made for it.
FolderLock lockCampaign(const std::string& dir)
{
	fs::path folder = fs::absolute(dir).lexically_normal();
	if (!folder.has_filename()) folder = folder.parent_path();
	ensureDirectory(folder.parent_path().string());
	return FolderLock(folder, LockWait::No, "this campaign");
}

/// The job list's text: built before anything is written, so a path no job
/// line can carry is refused with the campaign folder untouched.
std::string jobListText(const std::string& dir, const CampaignPlan& plan, const std::vector<CampaignJob>& jobs)
{
	std::string text;
	for (const auto& job : jobs) text += jobCommandLine(dir, plan, job) + "\n";
	return text;
}

void writeJobList(const std::string& path, const std::string& text)
{
	// A file set of its own kind: it replaces only a job list esif wrote.
	writeFileSet("a job list", {path}, {}, [&](const FileSet& set) {
		writeTextAtomically(set.staging(path), text);
		return 0;
	});
}
}  // namespace

int monteCarloCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd(
		"Monte Carlo campaign: simulates --runs noise draws of a scenario (noise seeds --seed0, --seed0 + 1, ...: "
		"new odometry and sensor noise on the same world and path) and runs every config on each, each run in "
		"its own process, --jobs at a time; then writes ANEES with its 95% chi-square bounds, RMSE and time per "
		"config (summary.md, summary.html, summary.csv, per_step.csv, landmarks.csv, anees_pose.png, rmse.png, "
		"landmark_anees.png) into --out. Re-running resumes (finished runs are kept, failed ones retried) and "
		"may add configs or runs. A failed run is recorded in DIR/failures/ and listed; the exit code is then "
		"that of the first failed run. --emit-jobs writes the runs as shell commands instead, for GNU "
		"parallel, xargs -P or a Slurm array; --collect DIR aggregates what has finished.",
		' ', ESIF_VERSION);
	TCLAP::ValueArg<std::string> scenario("s", "scenario", "scenario INI with a [simulation] section", false, "", "INI", cmd);
	TCLAP::ValueArg<std::string> configs("c", "configs", "comma-separated filter configs", false, "", "A.ini,B.ini,...", cmd);
	TCLAP::ValueArg<int> runs("n", "runs", "number of runs (noise seeds), 1 to 100000", false, 0, "N", cmd);
	TCLAP::ValueArg<std::string> out("o", "out", "campaign folder", false, "", "DIR", cmd);
	TCLAP::ValueArg<int> jobs("j", "jobs", "runs at a time, 1 to 256 (default: the number of cores)", false, 0, "J", cmd);
	TCLAP::ValueArg<int> seed0("", "seed0", "noise seed of the first run (default 1)", false, 1, "S", cmd);
	TCLAP::ValueArg<std::string> emit_jobs(
		"", "emit-jobs", "write one shell command per unfinished run to FILE instead of running them", false, "",
		"FILE", cmd);
	TCLAP::ValueArg<std::string> collect(
		"", "collect", "aggregate the finished runs of campaign folder DIR (and list the others)", false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> job(
		"", "job", "with --out DIR: run one job of the campaign in DIR (what an --emit-jobs line runs)", false, "",
		"CONFIG/seed_S", cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;
	// Runs are forks of the run server (RunServer.h), started before this
	// process opens a file or starts a thread, with the plugins already
	// loaded (PluginPreload.h).
	std::optional<RunServer> server;
	if (!collect.isSet() && !emit_jobs.isSet())
	{
		preloadPlugins();
		server.emplace(runMain);
	}

	const bool planning = scenario.isSet() || configs.isSet() || runs.isSet() || seed0.isSet();
	if (collect.isSet())
	{
		if (planning || out.isSet() || job.isSet() || emit_jobs.isSet() || jobs.isSet())
			throw ConfigError("esif montecarlo: --collect DIR takes no other option");
		requireNoLinksInCampaign(collect.getValue());
		collectAndReport(collect.getValue(), CampaignPlan::load(collect.getValue()));
		return 0;
	}
	if (!out.isSet()) throw ConfigError("esif montecarlo: --out DIR is required (or --collect DIR; see --help)");
	if (job.isSet())
	{
		if (planning || emit_jobs.isSet() || jobs.isSet())
			throw ConfigError("esif montecarlo: --job takes only --out (the campaign folder)");
		return runOneJob(out.getValue(), job.getValue());
	}
	if (!scenario.isSet() || !configs.isSet() || !runs.isSet())
		throw ConfigError("esif montecarlo: --scenario, --configs and --runs are required (see --help)");
	if (runs.getValue() < 1 || runs.getValue() > kMaxCampaignRuns)
		throw ConfigError("esif montecarlo: --runs " + std::to_string(runs.getValue()) + ": must be in [1, " +
						  std::to_string(kMaxCampaignRuns) + "]");
	if (seed0.getValue() < 0 || seed0.getValue() > INT_MAX - runs.getValue())
		throw ConfigError("esif montecarlo: --seed0 " + std::to_string(seed0.getValue()) + ": must be >= 0 and leave room for --runs seeds");
	if (jobs.isSet() && (jobs.getValue() < 1 || jobs.getValue() > kMaxCampaignJobs))
		throw ConfigError("esif montecarlo: --jobs " + std::to_string(jobs.getValue()) + ": must be in [1, " +
						  std::to_string(kMaxCampaignJobs) + "]");
	if (jobs.isSet() && emit_jobs.isSet())
		throw ConfigError("esif montecarlo: --jobs applies to local runs, not to --emit-jobs");
	const auto config_list = splitCommas(configs.getValue());
	if (config_list.empty()) throw ConfigError("esif montecarlo: --configs: no config file given");
	checkScenario(scenario.getValue());
	checkConfigs(config_list);

	const std::string dir = out.getValue();
	if (emit_jobs.isSet()) requireJobLinesPossible(dir);  // before anything is written
	std::vector<NamedInput> inputs{{"the scenario", scenario.getValue()}};
	for (const auto& c : config_list) inputs.push_back({"the config", c});
	requireOutputApart(dir, inputs);
	// The job list is not written into the campaign folder either: its files
	// are the campaign's (campaign.ini, the runs' stats.json).
	inputs.push_back({"the campaign folder", dir});
	if (emit_jobs.isSet()) requireOutputApart(emit_jobs.getValue(), inputs, "--emit-jobs");
	// Paths campaign.ini could not hold are refused before anything is written.
	const CampaignPlan requested =
		CampaignPlan::create(scenario.getValue(), config_list, seed0.getValue(), runs.getValue());
	const FolderLock campaign_lock = lockCampaign(dir);
	const CampaignPlan plan = planCampaign(dir, requested);
	requireNoLinksInCampaign(dir);
	const std::vector<CampaignJob> todo = unfinishedJobs(dir, plan);
	const std::string job_list = emit_jobs.isSet() ? jobListText(dir, plan, todo) : "";
	ensureDirectory(dir);
	writeTextAtomically(campaign_layout::manifest(dir), plan.iniText());
	if (emit_jobs.isSet())
	{
		writeJobList(emit_jobs.getValue(), job_list);
		std::cout << "esif montecarlo: " << todo.size() << " jobs written to " << emit_jobs.getValue() << " ("
				  << campaignJobs(plan).size() - todo.size() << " finished already); then: esif montecarlo --collect "
				  << dir << "\n";
		return 0;
	}
	const unsigned threads = jobs.isSet() ? static_cast<unsigned>(jobs.getValue())
										  : std::max(1u, std::thread::hardware_concurrency());
	std::cerr << "esif montecarlo: " << todo.size() << " runs to do (" << campaignJobs(plan).size() - todo.size()
			  << " finished before) on " << threads << " threads\n";
	const std::vector<JobOutcome> outcomes = runCampaignJobs(dir, plan, todo, threads);
	collectAndReport(dir, plan);
	for (const auto& o : outcomes)
		if (o.exit_code != 0) return o.exit_code;
	return 0;
}

}  // namespace esif::app
