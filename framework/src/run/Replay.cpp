#include <esif/core/Elapsed.h>
#include <esif/core/Errors.h>
#include <esif/io/ProgressBar.h>
#include <esif/run/Replay.h>

#include <chrono>
#include <cmath>
#include <new>
#include <stdexcept>

namespace esif
{
namespace
{
using Clock = SteadyClock;

/// A plugin that runs out of memory fails the run like a numerical failure
/// (exit code 3): the input is valid, but this estimator cannot carry on
/// with it, at a step the message names; a bad-input code (1) would send
/// the user looking for a fault in the rawlog or config.
NumericalError outOfMemory(
	const std::string& rawlog, const std::string& when, const std::string& plugin, std::size_t landmarks)
{
	return NumericalError(
		rawlog + ": out of memory " + when + " in plugin " + plugin + " (state of " + std::to_string(landmarks) +
		" landmarks)");
}

void checkReport(const StepReport& report, const StepInput& step, const std::string& plugin)
{
	const std::size_t expected = step.scan ? step.scan->measurements.size() : 0;
	if (report.associations.size() != expected)
		throw std::logic_error(
			"plugin " + plugin + " reported " + std::to_string(report.associations.size()) + " associations for " +
			std::to_string(expected) + " measurements at step " + std::to_string(step.index));
}

/// Puts a smoother's re-estimated poses in place of the online ones; the
/// keyframes keep the steps they were chosen at (by the online poses).
void applySmoothedTrajectory(const std::vector<PoseEstimate>& smoothed, RunRecord& record)
{
	if (smoothed.size() != record.trajectory.size())
		throw std::logic_error(
			"plugin " + record.plugin + " returned a smoothed trajectory of " + std::to_string(smoothed.size()) +
			" poses for " + std::to_string(record.trajectory.size()) + " steps");
	for (std::size_t k = 0; k < smoothed.size(); ++k) record.trajectory[k].pose = smoothed[k];
	for (auto& keyframe : record.keyframes) keyframe.pose = smoothed[keyframe.step];
}

/// Puts a joining filter's settled reports in place of the online ones and
/// audits them afresh; each must answer the same measurements as its
/// online counterpart. Landmark counts stay online (they time the steps).
void applyFinalReports(std::vector<StepReport> final_reports, const Rawlog& log, ReplayResult& out)
{
	const std::string& plugin = out.record.plugin;
	if (final_reports.size() != out.reports.size())
		throw std::logic_error(
			"plugin " + plugin + " returned " + std::to_string(final_reports.size()) + " final reports for " +
			std::to_string(out.reports.size()) + " steps");
	for (std::size_t k = 0; k < final_reports.size(); ++k)
		if (final_reports[k].associations.size() != out.reports[k].associations.size())
			throw std::logic_error(
				"plugin " + plugin + " returned a final report of " +
				std::to_string(final_reports[k].associations.size()) + " associations for " +
				std::to_string(out.reports[k].associations.size()) + " measurements at step " + std::to_string(k));
	out.reports = std::move(final_reports);
	out.audit = AssociationAudit();
	for (std::size_t k = 0; k < out.reports.size(); ++k) out.audit.record(out.reports[k], log.true_ids[k]);
}
}  // namespace

ReplayResult replay(FilterPlugin& plugin, const Rawlog& log, const ReplayOptions& options)
{
	ReplayResult out;
	out.record.plugin = plugin.GetRuntimeClass()->className;
	out.record.rawlog = log.path;
	out.step_us.reserve(log.steps.size());
	out.landmark_counts.reserve(log.steps.size());
	out.reports.reserve(log.steps.size());
	std::size_t landmarks = 0;
	out.record.trajectory.reserve(log.steps.size());

	ProgressBar progress(out.record.plugin, options.progress_bar ? log.steps.size() : 0);
	std::optional<Pose2> last_keyframe;
	const auto t_start = Clock::now();
	for (std::size_t k = 0; k < log.steps.size(); ++k)
	{
		const StepInput& step = log.steps[k];
		StepReport report;
		const auto t0 = Clock::now();
		try
		{
			report = plugin.processStep(step);
		}
		catch (const NumericalError& e)
		{
			throw NumericalError(log.path + ": step " + std::to_string(k) + ": " + e.what());
		}
		catch (const std::bad_alloc&)
		{
			throw outOfMemory(log.path, "at step " + std::to_string(k), out.record.plugin, landmarks);
		}
		out.step_us.push_back(microsecondsSince(t0));
		checkReport(report, step, out.record.plugin);
		out.reports.push_back(report);
		for (const auto& a : report.associations) landmarks += a.kind == Association::Kind::New;
		out.landmark_counts.push_back(landmarks);
		out.audit.record(report, log.true_ids[k]);

		const PoseEstimate pose = plugin.robotPose();
		out.record.trajectory.push_back({k, step.time_s, pose});
		const Pose2 p = toPose2(pose.mean);
		if (log.frames[k] &&
			(!last_keyframe || (p.head<2>() - last_keyframe->head<2>()).norm() >= options.keyframe_min_distance_m))
		{
			out.record.keyframes.push_back({pose, log.frames[k], k});
			last_keyframe = p;
		}
		progress.update(k + 1);
	}
	const auto t_finish = Clock::now();
	try
	{
		plugin.finish();
	}
	catch (const std::bad_alloc&)
	{
		throw outOfMemory(log.path, "after the last step", out.record.plugin, landmarks);
	}
	out.finish_us = microsecondsSince(t_finish);
	out.wall_s = microsecondsSince(t_start) * 1e-6;
	progress.finish();
	if (const auto smoothed = plugin.smoothedTrajectory()) applySmoothedTrajectory(*smoothed, out.record);
	if (auto final_reports = plugin.finalReports()) applyFinalReports(std::move(*final_reports), log, out);
	out.record.final_estimate = plugin.estimate();
	if (const auto* joiner = dynamic_cast<const LocalMapJoiner*>(&plugin)) out.fusion_costs = joiner->fusionCosts();
	return out;
}

}  // namespace esif
