/// \file MonteCarloJobs.cpp
/// Simulating and running a campaign's jobs as child processes; see MonteCarloJobs.h.

#include <esif/montecarlo/MonteCarloJobs.h>

#include <esif/core/Errors.h>
#include <esif/core/Text.h>
#include <esif/safeio/ChildProcess.h>

#include <esif/montecarlo/MonteCarloCollect.h>
#include <esif/run/ProgressBar.h>
#include <esif/safeio/AtomicFile.h>
#include <esif/safeio/FolderLock.h>
#include <esif/safeio/RunFolder.h>
#include <esif/safeio/TerminationCleanup.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <system_error>
#include <thread>

namespace fs = std::filesystem;

namespace esif
{
namespace
{
/// Simulates `noise_seed` into its sim folder unless it is there. Under
/// the seed's folder lock (processes of a job list and threads of the local
/// pool that need the same seed wait for the first), partial folders of
/// killed simulations are removed, then it is simulated into a partial
/// folder of this process and renamed into place in one step.
ChildResult ensureSimulation(const std::string& dir, const CampaignPlan& plan, int noise_seed)
{
	const fs::path folder = campaign_layout::simFolder(dir, noise_seed);
	std::error_code ec;
	if (fs::is_directory(folder, ec)) return {};
	ensureDirectory(folder.parent_path().string());
	const FolderLock lock(folder, LockWait::Yes);
	if (fs::is_directory(folder, ec)) return {};  // simulated while this job waited
	removeStalePartials(folder);
	const fs::path staging = partialFolderOf(folder);
	ensureDirectory(staging.string());
	termination::addPath(staging.string());
	const std::string rawlog = (staging / fs::path(campaign_layout::simRawlog(dir, noise_seed)).filename()).string();
	ChildResult result = runEsifChild(
		{"esif", "simulate", "--config", plan.scenario, "--noise-seed", std::to_string(noise_seed), "--out", rawlog},
		ChildOutput::Kept, "montecarlo");
	if (result.exit_code == 0 && std::rename(staging.c_str(), folder.c_str()) != 0)
	{
		result.exit_code = 1;
		result.error_line =
			"esif: error: " + folder.string() + ": cannot move the simulation into place: " + std::strerror(errno);
	}
	fs::remove_all(staging, ec);  // left only on failure
	termination::removePath(staging.string());
	if (result.exit_code != 0) result.error_line = "simulation: " + result.error_line;
	return result;
}

JobOutcome recordOutcome(
	const std::string& dir, const CampaignPlan& plan, const CampaignJob& job, const ChildResult& result)
{
	const std::string failure = campaign_layout::failureFile(dir, plan.names[job.config], job.noise_seed);
	JobOutcome outcome{campaign_layout::jobId(plan, job), false, result.exit_code, result.error_line};
	std::error_code ec;
	if (result.exit_code == 0)
		fs::remove(failure, ec);
	else
		try
		{
			writeFailureRecord(failure, {result.exit_code, result.error_line, result.stderr_text});
		}
		catch (...)
		{
			// A full disk: the run's own failure is the news; that it could not
			// be recorded is said with it.
			outcome.error_line += " (and its failure record could not be written: " +
								  reportCurrentException().line + ")";
		}
	return outcome;
}

/// runCampaignJob, with anything it throws (a folder it cannot create, no
/// descriptor left for a pipe, a full disk) made the job's failure: an
/// exception leaving a worker thread would end esif with SIGABRT.
JobOutcome runCampaignJobCaught(const std::string& dir, const CampaignPlan& plan, const CampaignJob& job)
{
	try
	{
		return runCampaignJob(dir, plan, job);
	}
	catch (...)
	{
		const FailureReport failure = reportCurrentException();
		return recordOutcome(dir, plan, job, {failure.exit_code, failure.line, failure.line + "\n"});
	}
}

/// `word` single-quoted for sh, bash and GNU parallel. A job line must stay
/// one line whatever a path holds: the engines read one job per line
/// (xargs -d '\n', parallel, `sed -n Np | bash`), so a line break inside
/// quotes would still end the job there and run the rest as a command of
/// its own. A word with a control character is refused, naming `what`.
std::string quoted(const std::string& word, const std::string& what)
{
	if (holdsControlCharacter(word))
		throw ConfigError(
			"esif montecarlo: " + what + " '" + printableToken(word) +
			"' holds a line break or another control character: a job line cannot carry it (engines read one job "
			"per line); rename it");
	std::string out = "'";
	for (const char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
	return out + "'";
}
/// "'ESIF' montecarlo --out 'DIR' --job ", the part every job line shares.
std::string jobLinePrefix(const std::string& dir)
{
	std::error_code ec;
	const std::string self = fs::read_symlink("/proc/self/exe", ec).string();
	return quoted(self, "the esif binary") + " montecarlo --out " +
		   quoted(fs::absolute(dir).lexically_normal().string(), "--out") + " --job ";
}
}  // namespace

JobOutcome runCampaignJob(const std::string& dir, const CampaignPlan& plan, const CampaignJob& job)
{
	const std::string id = campaign_layout::jobId(plan, job);
	const std::string out = campaign_layout::runFolder(dir, plan.names[job.config], job.noise_seed);
	ensureDirectory(fs::path(out).parent_path().string());
	// A job another process runs (a worker of a job list, a campaign on the
	// same folder) is left to it: its run is not this one's failure.
	const FolderLock running(out + ".job", LockWait::Try);
	if (!running.held()) return {id, true, 0, "running in another esif process"};
	if (inspectJob(dir, plan, job).state == JobState::Finished)
	{
		std::error_code ec;
		fs::remove(campaign_layout::failureFile(dir, plan.names[job.config], job.noise_seed), ec);  // a stale one
		return {id, true, 0, ""};
	}
	const ChildResult sim = ensureSimulation(dir, plan, job.noise_seed);
	if (sim.exit_code != 0) return recordOutcome(dir, plan, job, sim);
	const ChildResult run = runEsifChild(
		{"esif", "run", "--quiet", "--no-figures", "--config", plan.configs[job.config], "--rawlog",
		 campaign_layout::simRawlog(dir, job.noise_seed), "--out", out},
		ChildOutput::Kept, "montecarlo");
	return recordOutcome(dir, plan, job, run);
}

std::vector<JobOutcome> runCampaignJobs(
	const std::string& dir, const CampaignPlan& plan, const std::vector<CampaignJob>& jobs, unsigned threads)
{
	std::vector<JobOutcome> outcomes(jobs.size());
	std::atomic<std::size_t> next{0}, done{0};
	std::mutex report;
	ProgressBar bar("montecarlo", jobs.size(), true);
	bar.update(0);
	const auto work = [&] {
		for (std::size_t i; (i = next++) < jobs.size();)
		{
			outcomes[i] = runCampaignJobCaught(dir, plan, jobs[i]);
			std::lock_guard<std::mutex> lock(report);
			if (outcomes[i].exit_code != 0)
			{
				if (bar.enabled()) std::cerr << "\r\033[K";
				std::cerr << "esif montecarlo: " << outcomes[i].id << " failed (exit " << outcomes[i].exit_code
						  << "): " << outcomes[i].error_line << "\n";
			}
			bar.update(++done);
		}
	};
	std::vector<std::thread> pool;
	try
	{
		for (std::size_t t = 0; t < std::min<std::size_t>(std::max(1u, threads), jobs.size()); ++t)
			pool.emplace_back(work);
	}
	catch (const std::system_error& e)
	{
		// The system's thread limit: go on with the threads that started.
		std::cerr << "esif montecarlo: warning: " << pool.size() << " of " << threads
				  << " threads could be started (" << e.what() << ")\n";
	}
	if (pool.empty()) work();
	for (auto& t : pool) t.join();
	bar.finish();
	return outcomes;
}

std::string jobCommandLine(const std::string& dir, const CampaignPlan& plan, const CampaignJob& job)
{
	return jobLinePrefix(dir) + quoted(campaign_layout::jobId(plan, job), "the job");
}

void requireJobLinesPossible(const std::string& dir) { jobLinePrefix(dir); }

}  // namespace esif
