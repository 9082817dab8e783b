/// \file MonteCarloJobs.cpp
/// Simulating and running a campaign's jobs as child processes; see MonteCarloJobs.h.

#include "MonteCarloJobs.h"

#include "ChildProcess.h"

#include <esif/io/AtomicFile.h>
#include <esif/io/ProgressBar.h>
#include <esif/io/TerminationCleanup.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <thread>
#include <unistd.h>

namespace fs = std::filesystem;

namespace esif::app
{
namespace
{
/// A partial simulation folder beside the final one, unique to this
/// process and call.
std::string simStaging(const std::string& final_folder)
{
	static std::atomic<unsigned> counter{0};
	const fs::path f(final_folder);
	return (f.parent_path() / ("." + f.filename().string() + ".partial-" + std::to_string(::getpid()) + "-" +
							   std::to_string(counter++)))
		.string();
}

/// Simulates `noise_seed` into its sim folder unless it is there: into a
/// partial folder first, then renamed into place in one step.
ChildResult ensureSimulation(const std::string& dir, const CampaignPlan& plan, int noise_seed)
{
	const std::string folder = campaign_layout::simFolder(dir, noise_seed);
	std::error_code ec;
	if (fs::is_directory(folder, ec)) return {};
	const std::string staging = simStaging(folder);
	ensureDirectory(staging);
	termination::addPath(staging);
	const std::string rawlog = (fs::path(staging) / fs::path(campaign_layout::simRawlog(dir, noise_seed)).filename()).string();
	ChildResult result = runEsifChild(
		{"esif", "simulate", "--config", plan.scenario, "--noise-seed", std::to_string(noise_seed), "--out", rawlog},
		ChildOutput::Kept, "montecarlo");
	if (result.exit_code == 0 && std::rename(staging.c_str(), folder.c_str()) != 0 && errno != EEXIST &&
		errno != ENOTEMPTY)
	{
		result.exit_code = 1;
		result.error_line = "esif: error: " + folder + ": cannot move the simulation into place: " + std::strerror(errno);
	}
	fs::remove_all(staging, ec);  // left only when another job put its copy in place first, or on failure
	termination::removePath(staging);
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
		writeFailureRecord(failure, {result.exit_code, result.error_line, result.stderr_text});
	return outcome;
}

std::string quoted(const std::string& word)
{
	std::string out = "'";
	for (const char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
	return out + "'";
}
}  // namespace

std::mutex& SimulationLocks::forSeed(int noise_seed)
{
	std::lock_guard<std::mutex> lock(mutex_);
	auto& slot = locks_[noise_seed];
	if (!slot) slot = std::make_unique<std::mutex>();
	return *slot;
}

JobOutcome runCampaignJob(
	const std::string& dir, const CampaignPlan& plan, const CampaignJob& job, SimulationLocks& locks)
{
	if (jobState(dir, plan, job) == JobState::Finished) return {campaign_layout::jobId(plan, job), true, 0, ""};
	{
		std::lock_guard<std::mutex> lock(locks.forSeed(job.noise_seed));
		const ChildResult sim = ensureSimulation(dir, plan, job.noise_seed);
		if (sim.exit_code != 0) return recordOutcome(dir, plan, job, sim);
	}
	const std::string out = campaign_layout::runFolder(dir, plan.names[job.config], job.noise_seed);
	ensureDirectory(fs::path(out).parent_path().string());
	const ChildResult run = runEsifChild(
		{"esif", "run", "--quiet", "--config", plan.configs[job.config], "--rawlog",
		 campaign_layout::simRawlog(dir, job.noise_seed), "--out", out},
		ChildOutput::Kept, "montecarlo");
	return recordOutcome(dir, plan, job, run);
}

std::vector<JobOutcome> runCampaignJobs(
	const std::string& dir, const CampaignPlan& plan, const std::vector<CampaignJob>& jobs, unsigned threads)
{
	std::vector<JobOutcome> outcomes(jobs.size());
	SimulationLocks locks;
	std::atomic<std::size_t> next{0}, done{0};
	std::mutex report;
	ProgressBar bar("montecarlo", jobs.size(), true);
	bar.update(0);
	const auto work = [&] {
		for (std::size_t i; (i = next++) < jobs.size();)
		{
			outcomes[i] = runCampaignJob(dir, plan, jobs[i], locks);
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
	for (unsigned t = 0; t < std::max(1u, threads); ++t) pool.emplace_back(work);
	for (auto& t : pool) t.join();
	bar.finish();
	return outcomes;
}

std::string jobCommandLine(const std::string& dir, const CampaignPlan& plan, const CampaignJob& job)
{
	std::error_code ec;
	const std::string self = fs::read_symlink("/proc/self/exe", ec).string();
	return quoted(self) + " montecarlo --out " + quoted(fs::absolute(dir).lexically_normal().string()) + " --job " +
		   quoted(campaign_layout::jobId(plan, job));
}

}  // namespace esif::app
