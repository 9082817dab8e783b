#include "ReplayLoop.h"

#include <esif/core/Errors.h>
#include <esif/eval/MapOspa.h>
#include <esif/formats/RawlogSteps.h>
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

/// The steps of a log in order, from memory or read again from its file
/// (one held at a time), each prepared as the options say.
class StepFeed
{
   public:
	StepFeed(const Rawlog& log, const std::function<void(StepInput&)>& prepare) : log_(log), prepare_(prepare)
	{
		if (log.stepsLeftInFile())
			stream_.emplace(*log.source, "the replay reads its steps from it one at a time");
	}

	/// Step k (k = 0, 1, ... in turn).
	const StepInput& step(std::size_t k)
	{
		if (stream_) current_ = std::move(stream_->next().input);
		else if (prepare_) current_ = log_.steps[k];
		else return log_.steps[k];
		if (prepare_) prepare_(current_);
		return current_;
	}

	/// After the last step: the file still held what the first read gave.
	void finish()
	{
		if (stream_) stream_->finish();
	}

   private:
	const Rawlog& log_;
	const std::function<void(StepInput&)>& prepare_;
	std::optional<RawlogStepStream> stream_;
	StepInput current_;
};

/// Puts a joining filter's settled reports in place of the online ones and
/// audits them afresh; each must answer the same measurements as its
/// online counterpart. Landmark counts stay online (they time the steps).
void applyFinalReports(std::vector<StepReport> final_reports, const Rawlog& log, const std::vector<bool>& id_given,
					   ReplayResult& out)
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
	std::size_t first = 0;
	for (std::size_t k = 0; k < out.reports.size(); ++k)
	{
		out.audit.record(out.reports[k], log.true_ids[k]);
		out.audit.recordGivenIds(out.reports[k], id_given, first);
		first += out.reports[k].associations.size();
	}
}
}  // namespace

ReplayResult replay(FilterPlugin& plugin, const Rawlog& log, const ReplayOptions& options)
{
	ReplayResult out;
	out.record.plugin = plugin.GetRuntimeClass()->className;
	out.record.rawlog = log.path;
	out.record.frames_source = log.source;
	const std::size_t steps = log.stepCount();
	out.landmark_counts.reserve(steps);
	out.reports.reserve(steps);
	out.record.trajectory.reserve(steps);
	std::size_t landmarks = 0;
	std::optional<Pose2> last_keyframe;
	StepReport report;
	StepFeed feed(log, options.prepare);
	const StepInput* step = nullptr;
	// Which measurements reached the plugin with an ID, for final reports.
	std::vector<bool> id_given;
	id_given.reserve(log.measurement_count);
	OspaCutoff ospa;

	ReplaySource source;
	source.origin = log.path;
	source.plugin = out.record.plugin;
	source.count = steps;
	source.input_name = "step";
	source.input_number = [](std::size_t k) { return k; };
	// Each step is fetched outside the timed part: reading it again from the
	// file is not the plugin's time.
	if (steps > 0) step = &feed.step(0);
	source.feed = [&](std::size_t) { report = plugin.processStep(*step); };
	source.after = [&](std::size_t k) {
		checkReport(report, *step, out.record.plugin);
		out.reports.push_back(report);
		for (const auto& a : report.associations) landmarks += a.kind == Association::Kind::New;
		out.landmark_counts.push_back(landmarks);
		out.audit.record(report, log.true_ids[k]);
		out.audit.recordGivenIds(report, *step);
		ospa.add(*step);
		if (step->scan)
			for (const auto& m : step->scan->measurements) id_given.push_back(m.id.has_value());

		const PoseEstimate pose = plugin.robotPose();
		out.record.trajectory.push_back({k, step->time_s, pose});
		const Pose2 p = pose.mean;
		// A step with a scan has a sensory frame, kept or to be read again.
		if (step->scan &&
			(!last_keyframe || (p.head<2>() - last_keyframe->head<2>()).norm() >= options.keyframe_min_distance_m))
		{
			out.record.keyframes.push_back({pose, k < log.frames.size() ? log.frames[k] : nullptr, k});
			last_keyframe = p;
		}
		if (k + 1 < steps) step = &feed.step(k + 1);
	};
	source.state = [&] { return std::to_string(landmarks) + " landmarks"; };
	ReplayTimes times = runReplayLoop(plugin, source, options.progress_bar);
	feed.finish();
	out.step_us = std::move(times.feed_us);
	out.finish_us = times.finish_us;
	out.wall_s = times.wall_s;
	out.ospa_cutoff_m = ospa.value();

	if (const auto smoothed = plugin.smoothedTrajectory()) applySmoothedTrajectory(*smoothed, out.record);
	if (auto final_reports = plugin.finalReports())
		applyFinalReports(std::move(*final_reports), log, id_given, out);
	out.record.final_estimate = plugin.estimate();
	if (const auto* joiner = dynamic_cast<const LocalMapJoiner*>(&plugin)) out.fusion_costs = joiner->fusionCosts();
	return out;
}

}  // namespace esif
