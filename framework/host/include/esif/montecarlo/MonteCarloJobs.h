#pragma once
/// \file MonteCarloJobs.h
/// The runs of a Monte Carlo campaign (MonteCarloCampaign.h) as child
/// processes: a job simulates its noise seed if no other job has (`esif
/// simulate`), then replays its config on it (`esif run`). The same job is
/// what one line of --emit-jobs runs (`esif montecarlo --out DIR --job ID`)
/// and what the local pool runs on --jobs threads.

#include <esif/montecarlo/MonteCarloCampaign.h>

#include <string>
#include <vector>

namespace esif
{
struct JobOutcome
{
	std::string id;	 ///< "ekf/seed_0007"
	bool skipped = false;  ///< not run: finished before, or running in another esif process (error_line says so)
	int exit_code = 0;	///< 0: finished
	std::string error_line;
};

/// Runs one job in `dir`; a failure (of the simulation or the run) is
/// recorded in its failure file, a success removes an earlier record.
JobOutcome runCampaignJob(const std::string& dir, const CampaignPlan& plan, const CampaignJob& job);

/// Largest --jobs: every job is a child process of up to a few hundred MB.
inline constexpr int kMaxCampaignJobs = 256;

/// Runs `jobs` on `threads` threads (no more than there are jobs; fewer
/// when the system cannot start that many) with a progress bar and a time-left
/// estimate on stderr (when it is a terminal); a failed job is reported
/// on a line of its own as it happens. Returns the outcomes in job order.
std::vector<JobOutcome> runCampaignJobs(
	const std::string& dir, const CampaignPlan& plan, const std::vector<CampaignJob>& jobs, unsigned threads);

/// The shell command that runs `job` on its own: the absolute esif binary,
/// `montecarlo --out DIR --job ID`, each word single-quoted. ConfigError
/// when a word holds a line break or another control character: the
/// engines read one job per line, so no byte of a path may end one.
std::string jobCommandLine(const std::string& dir, const CampaignPlan& plan, const CampaignJob& job);

/// Throws that ConfigError now when a job line of the campaign in `dir`
/// could not be written (the esif binary's path or `dir` holds a control
/// character): checked before anything is written.
void requireJobLinesPossible(const std::string& dir);

}  // namespace esif
