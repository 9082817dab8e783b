#pragma once
/// \file MonteCarloJobs.h
/// The runs of a Monte Carlo campaign (MonteCarloCampaign.h) as child
/// processes: a job simulates its noise seed if no other job has (`esif
/// simulate`), then replays its config on it (`esif run`). The same job is
/// what one line of --emit-jobs runs (`esif montecarlo --out DIR --job ID`)
/// and what the local pool runs on --jobs threads.

#include <esif/run/MonteCarloCampaign.h>

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace esif::app
{
struct JobOutcome
{
	std::string id;	 ///< "ekf/seed_0007"
	bool skipped = false;  ///< finished before: not run again
	int exit_code = 0;	///< 0: finished
	std::string error_line;
};

/// Keeps threads of one process from simulating the same noise seed twice
/// (processes of a job list may: the simulation folder is put in place by
/// one rename, so the first one wins and the others' copy is dropped).
class SimulationLocks
{
   public:
	std::mutex& forSeed(int noise_seed);

   private:
	std::mutex mutex_;
	std::map<int, std::unique_ptr<std::mutex>> locks_;
};

/// Runs one job in `dir`; a failure (of the simulation or the run) is
/// recorded in its failure file, a success removes an earlier record.
JobOutcome runCampaignJob(
	const std::string& dir, const CampaignPlan& plan, const CampaignJob& job, SimulationLocks& locks);

/// Runs `jobs` on `threads` threads with a progress bar and a time-left
/// estimate on stderr (when it is a terminal); a failed job is reported
/// on a line of its own as it happens. Returns the outcomes in job order.
std::vector<JobOutcome> runCampaignJobs(
	const std::string& dir, const CampaignPlan& plan, const std::vector<CampaignJob>& jobs, unsigned threads);

/// The shell command that runs `job` on its own: the absolute esif binary,
/// `montecarlo --out DIR --job ID`, each word single-quoted.
std::string jobCommandLine(const std::string& dir, const CampaignPlan& plan, const CampaignJob& job);

}  // namespace esif::app
