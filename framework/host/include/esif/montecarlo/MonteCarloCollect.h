#pragma once
/// \file MonteCarloCollect.h
/// Aggregates whatever a campaign folder holds (MonteCarloCampaign.h): the
/// finished runs of every config into their statistics
/// (MonteCarloStatistics.h), the failed and unfinished ones into a list,
/// and writes the tables and figures into the folder.

#include <esif/eval/MonteCarloStatistics.h>
#include <esif/montecarlo/MonteCarloTables.h>
#include <esif/montecarlo/MonteCarloCampaign.h>

#include <optional>
#include <string>
#include <vector>

namespace esif
{
struct CampaignCollection
{
	std::vector<ConfigStatistics> configs;	///< the configs with at least one finished run, in plan order
	CampaignGaps gaps;
	std::size_t finished = 0;
	std::size_t total = 0;
};

/// Reads every finished run of `plan` in `dir`. A finished run folder whose
/// files cannot be read back (cut, changed, out of bounds) is damaged: it is
/// listed among the runs not aggregated, naming the file, and the next run
/// of the campaign redoes it (inspectJob).
CampaignCollection collectCampaign(const std::string& dir, const CampaignPlan& plan);

/// The run's errors and figures from its finished run folder; InputError
/// naming the file when one is missing or malformed.
CampaignRunErrors readCampaignRun(const std::string& run_folder, std::size_t seed_index);

/// A job as the campaign folder holds it. A run folder with stats.json is
/// finished only when its files read back; otherwise it is damaged, and
/// counts as not run: one damaged file must not stop the resume or
/// --collect, nor be aggregated.
struct JobInspection
{
	JobState state = JobState::Pending;
	std::optional<CampaignRunErrors> run;  ///< a finished run, read
	std::optional<std::string> damage;	///< why a run folder with stats.json is not a finished run
};

JobInspection inspectJob(const std::string& dir, const CampaignPlan& plan, const CampaignJob& job);

/// summary.csv, summary.md, per_step.csv, landmarks.csv and the figures
/// (MonteCarloFigures.h), then summary.html (MonteCarloPage.h), into `dir`,
/// each atomically; returns summary.md's text.
std::string writeCampaignOutputs(const std::string& dir, const CampaignPlan& plan, const CampaignCollection& c);

}  // namespace esif
