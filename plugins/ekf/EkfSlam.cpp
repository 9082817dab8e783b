#include "EkfSlam.h"

IMPLEMENTS_MRPT_OBJECT(EkfSlam, FilterPlugin, esif)

namespace esif
{
void EkfSlam::start()
{
	filter_ = LandmarkEkf(params_.association, 0, params_.jacobians);
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
	filter_.rejections().appendCounters(c.counters, "");
	return c;
}

}  // namespace esif
