#include "EkfSlam.h"

IMPLEMENTS_MRPT_OBJECT(EkfSlam, FilterPlugin, esif)

namespace esif
{
void EkfSlam::start()
{
	filter_ = LandmarkEkf(params_.association, 0, params_.jacobians);
	reports_.clear();
}

StepReport EkfSlam::processStep(const StepInput& step)
{
	StepReport report = filter_.processStep(step);
	if (params_.association.merge_landmarks_after_matches > 0) reports_.push_back(report);
	return report;
}

std::optional<std::vector<StepReport>> EkfSlam::finalReports() const
{
	if (filter_.landmarkMerges() == 0) return std::nullopt;
	std::vector<StepReport> out = reports_;
	for (auto& report : out)
		for (auto& a : report.associations)
			if (a.id >= 0) a.id = filter_.finalId(a.id);
	return out;
}

CostFigures EkfSlam::costFigures() const
{
	CostFigures c;
	c.state_dim = filter_.core().stateDim();
	c.poses_in_state = 1;  // the current robot pose
	c.counters.emplace_back("jcbb_nodes", static_cast<double>(filter_.jcbbNodes()));
	c.counters.emplace_back("jcbb_fallbacks", static_cast<double>(filter_.jcbbFallbacks()));
	c.counters.emplace_back("id_gate_rejected", static_cast<double>(filter_.idGateRejections()));
	c.counters.emplace_back("id_gate_dropped", static_cast<double>(filter_.idGateDrops()));
	c.counters.emplace_back("iterated_updates", static_cast<double>(filter_.iteratedUpdates()));
	c.counters.emplace_back("relinearisations", static_cast<double>(filter_.relinearisations()));
	c.counters.emplace_back("iterations_stopped_uphill", static_cast<double>(filter_.iterationsStoppedUphill()));
	c.counters.emplace_back("landmark_merges", static_cast<double>(filter_.landmarkMerges()));
	filter_.rejections().appendCounters(c.counters, "");
	return c;
}

}  // namespace esif
