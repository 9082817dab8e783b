/// \file MonteCarloCollect.cpp
/// Reading a campaign folder into statistics and writing its outputs; see
/// MonteCarloCollect.h.

#include <esif/core/Errors.h>
#include <esif/core/InputBounds.h>
#include <esif/eval/EstimationErrorFiles.h>
#include "montecarlo/MonteCarloFigures.h"
#include <esif/eval/SuspectResult.h>
#include <esif/formats/StatsJson.h>
#include <esif/montecarlo/MonteCarloPage.h>
#include <esif/montecarlo/MonteCarloCollect.h>
#include <esif/safeio/AtomicFile.h>
#include <esif/safeio/FileSet.h>

#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;

namespace esif
{
namespace
{
constexpr int kFigureWidthPx = 1200;

/// Largest count a run's stats.json may hold: summed over thousands of
/// runs it still fits a long long exactly.
constexpr double kMaxCount = 1e12;

/// stats.json `key` (nullopt when absent or null), which must be a number in
/// [0, `max`]: a damaged file is one error naming it, never summed as it is.
std::optional<double> scoreValue(const Stats& stats, const std::string& key, double max, const std::string& path)
{
	const auto v = stats.number(key);
	if (v && !(*v >= 0 && *v <= max))
		throw InputError(path + ": " + key + " = " + statText(*stats.get(key)) + " is outside [0, " +
						 statText(StatValue(max)) + "]");
	return v;
}

/// Every file writeCampaignOutputs may write (the figures with their SVG
/// twins), summary.csv first: it names the set.
constexpr const char* kCampaignOutputFiles[] = {
	"summary.csv", "summary.md", "per_step.csv", "landmarks.csv", "summary.html", "anees_pose.png",
	"anees_pose.svg", "rmse.png", "rmse.svg", "landmark_anees.png", "landmark_anees.svg"};

/// "ID: failed (exit N): first error line" from the job's failure record;
/// a damaged record still says that the run failed.
std::string failedLine(const std::string& id, const std::string& record_path)
{
	try
	{
		const FailureRecord r = readFailureRecord(record_path);
		return id + ": failed (exit " + std::to_string(r.exit_code) + "): " + r.error_line;
	}
	catch (const InputError& e)
	{
		return id + ": failed (its failure record cannot be read: " + e.what() + ")";
	}
}
}  // namespace

CampaignRunErrors readCampaignRun(const std::string& run_folder, std::size_t seed_index)
{
	const fs::path d(run_folder);
	CampaignRunErrors run;
	run.seed_index = seed_index;
	run.poses = readPoseErrors((d / kPoseErrorsFile).string());
	run.landmarks = readLandmarkErrors((d / kLandmarkErrorsFile).string());
	const std::string stats_path = (d / "stats.json").string();
	const Stats stats = Stats::load(stats_path);
	const auto wall = stats.number("wall_s");
	if (!wall || !std::isfinite(*wall) || *wall < 0) throw InputError(stats_path + ": no wall_s, or not a time");
	run.wall_s = *wall;
	run.da_wrong = static_cast<long long>(stats.number("da_wrong").value_or(0));
	run.suspect_reason = recordedSuspectReason(stats);
	run.landmarks_true = scoreValue(stats, "landmarks_true", kMaxCount, stats_path);
	run.landmarks_found = scoreValue(stats, "landmarks_found", kMaxCount, stats_path);
	run.landmarks_duplicated = scoreValue(stats, "landmarks_duplicated", kMaxCount, stats_path);
	run.landmarks_spurious = scoreValue(stats, "landmarks_spurious", kMaxCount, stats_path);
	run.da_precision = scoreValue(stats, "da_precision", 1, stats_path);
	run.da_recall = scoreValue(stats, "da_recall", 1, stats_path);
	run.landmark_ospa_m = scoreValue(stats, "landmark_ospa_m", kMaxCoordinate_m, stats_path);
	run.state_nees = stats.number("state_nees");
	if (run.state_nees && !(std::isfinite(*run.state_nees) && *run.state_nees >= 0))
		throw InputError(stats_path + ": state_nees is not a finite number >= 0");
	if (run.state_nees) run.state_nees_dof = static_cast<std::size_t>(stats.number("state_nees_dof").value_or(0));
	return run;
}

JobInspection inspectJob(const std::string& dir, const CampaignPlan& plan, const CampaignJob& job)
{
	JobInspection out;
	out.state = jobState(dir, plan, job);
	if (out.state != JobState::Finished) return out;
	try
	{
		out.run = readCampaignRun(
			campaign_layout::runFolder(dir, plan.names[job.config], job.noise_seed),
			static_cast<std::size_t>(job.noise_seed - plan.seed0));
	}
	catch (const InputError& e)
	{
		out.state = JobState::Pending;
		out.damage = e.what();
	}
	return out;
}

CampaignCollection collectCampaign(const std::string& dir, const CampaignPlan& plan)
{
	CampaignCollection out;
	out.gaps.planned = static_cast<std::size_t>(plan.runs);
	std::vector<std::vector<CampaignRunErrors>> by_config(plan.configs.size());
	for (const auto& job : campaignJobs(plan))
	{
		++out.total;
		const std::string id = campaign_layout::jobId(plan, job);
		const std::string& name = plan.names[job.config];
		JobInspection inspected = inspectJob(dir, plan, job);
		switch (inspected.state)
		{
			case JobState::Finished:
				by_config[job.config].push_back(std::move(*inspected.run));
				if (const auto& reason = by_config[job.config].back().suspect_reason)
					out.gaps.suspect.push_back(id + ": suspect: " + *reason);
				++out.finished;
				break;
			case JobState::Failed:
				out.gaps.failed.push_back(failedLine(id, campaign_layout::failureFile(dir, name, job.noise_seed)));
				break;
			case JobState::Pending:
				out.gaps.pending.push_back(
					id + (inspected.damage ? ": damaged, redone by the next run of the campaign: " + *inspected.damage
										   : ": not finished"));
				break;
		}
	}
	for (std::size_t c = 0; c < plan.configs.size(); ++c)
		if (!by_config[c].empty()) out.configs.push_back(aggregateRuns(plan.names[c], by_config[c]));
	return out;
}

std::string writeCampaignOutputs(const std::string& dir, const CampaignPlan& plan, const CampaignCollection& c)
{
	const std::string title = fs::path(plan.scenario).stem().string() + ", noise seeds " + std::to_string(plan.seed0) +
							  ".." + std::to_string(plan.seed0 + plan.runs - 1);
	const std::string markdown = monteCarloSummaryMarkdown("esif montecarlo: " + title, c.configs, c.gaps);
	std::vector<std::string> files;
	for (const char* name : kCampaignOutputFiles) files.push_back((fs::path(dir) / name).string());
	// One set: a full disk halfway leaves the previous summary whole, never
	// a summary.csv of N + 1 runs beside a summary.html of N.
	writeFileSet("the summary of a campaign", files, {}, [&](const FileSet& set) {
		const fs::path d(set.stagingFolder());
		writeTextAtomically((d / "summary.csv").string(), monteCarloSummaryCsv(c.configs, c.gaps.planned));
		writeTextAtomically((d / "summary.md").string(), markdown);
		writeTextAtomically((d / "per_step.csv").string(), monteCarloPerStepCsv(c.configs));
		writeTextAtomically((d / "landmarks.csv").string(), monteCarloLandmarksCsv(c.configs));
		writeMonteCarloFigures(c.configs, title, d.string(), kFigureWidthPx);
		// After the figures it inlines.
		writeMonteCarloPage("esif montecarlo: " + title, c.configs, c.gaps, d.string());
		return 0;
	});
	return markdown;
}

}  // namespace esif
