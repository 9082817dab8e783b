#include "ReplayLoop.h"

#include <esif/core/Errors.h>
#include <esif/run/Replay.h>

#include <cmath>
#include <stdexcept>

namespace esif
{
namespace
{
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
	for (std::size_t k = 0; k < out.reports.size(); ++k)
	{
		out.audit.record(out.reports[k], log.true_ids[k]);
		out.audit.recordGivenIds(out.reports[k], log.steps[k]);
	}
}
}  // namespace

ReplayResult replay(FilterPlugin& plugin, const Rawlog& log, const ReplayOptions& options)
{
	ReplayResult out;
	out.record.plugin = plugin.GetRuntimeClass()->className;
	out.record.rawlog = log.path;
	out.record.frames_source = log.source;
	out.landmark_counts.reserve(log.steps.size());
	out.reports.reserve(log.steps.size());
	out.record.trajectory.reserve(log.steps.size());
	std::size_t landmarks = 0;
	std::optional<Pose2> last_keyframe;
	StepReport report;

	ReplaySource source;
	source.origin = log.path;
	source.plugin = out.record.plugin;
	source.count = log.steps.size();
	source.input_name = "step";
	source.input_number = [](std::size_t k) { return k; };
	source.feed = [&](std::size_t k) { report = plugin.processStep(log.steps[k]); };
	source.after = [&](std::size_t k) {
		const StepInput& step = log.steps[k];
		checkReport(report, step, out.record.plugin);
		out.reports.push_back(report);
		for (const auto& a : report.associations) landmarks += a.kind == Association::Kind::New;
		out.landmark_counts.push_back(landmarks);
		out.audit.record(report, log.true_ids[k]);
		out.audit.recordGivenIds(report, step);

		const PoseEstimate pose = plugin.robotPose();
		out.record.trajectory.push_back({k, step.time_s, pose});
		const Pose2 p = pose.mean;
		// A step with a scan has a sensory frame, kept or to be read again.
		if (step.scan &&
			(!last_keyframe || (p.head<2>() - last_keyframe->head<2>()).norm() >= options.keyframe_min_distance_m))
		{
			out.record.keyframes.push_back({pose, k < log.frames.size() ? log.frames[k] : nullptr, k});
			last_keyframe = p;
		}
	};
	source.state = [&] { return std::to_string(landmarks) + " landmarks"; };
	ReplayTimes times = runReplayLoop(plugin, source, options.progress_bar);
	out.step_us = std::move(times.feed_us);
	out.finish_us = times.finish_us;
	out.wall_s = times.wall_s;

	if (const auto smoothed = plugin.smoothedTrajectory()) applySmoothedTrajectory(*smoothed, out.record);
	if (auto final_reports = plugin.finalReports()) applyFinalReports(std::move(*final_reports), log, out);
	out.record.final_estimate = plugin.estimate();
	if (const auto* joiner = dynamic_cast<const LocalMapJoiner*>(&plugin)) out.fusion_costs = joiner->fusionCosts();
	return out;
}

}  // namespace esif
