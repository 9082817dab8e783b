#pragma once
/// \file MonteCarloCollect.h
/// Aggregates whatever a campaign folder holds (MonteCarloCampaign.h): the
/// finished runs of every config into their statistics
/// (MonteCarloStatistics.h), the failed and unfinished ones into a list,
/// and writes the tables and figures into the folder.

#include <esif/eval/MonteCarloStatistics.h>
#include <esif/eval/MonteCarloTables.h>
#include <esif/run/MonteCarloCampaign.h>

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

/// Reads every finished run of `plan` in `dir`. A finished run folder with
/// a missing or malformed file is an InputError naming the file.
CampaignCollection collectCampaign(const std::string& dir, const CampaignPlan& plan);

/// The run's errors and figures from its finished run folder.
CampaignRunErrors readCampaignRun(const std::string& run_folder, std::size_t seed_index);

/// summary.csv, summary.md, per_step.csv, landmarks.csv and the figures
/// (MonteCarloFigures.h), then summary.html (MonteCarloPage.h), into `dir`,
/// each atomically; returns summary.md's text.
std::string writeCampaignOutputs(const std::string& dir, const CampaignPlan& plan, const CampaignCollection& c);

}  // namespace esif
