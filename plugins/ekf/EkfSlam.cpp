#include "EkfSlam.h"

IMPLEMENTS_MRPT_OBJECT(EkfSlam, FilterPlugin, esif)

namespace esif
{
void EkfSlam::configure(const ConfigSection& section)
{
	loadParams(params_, section);
	filter_ = LandmarkEkf(params_);
}

CostFigures EkfSlam::costFigures() const
{
	CostFigures c;
	c.state_dim = filter_.core().stateDim();
	c.poses_in_state = 1;  // the current robot pose
	c.counters.emplace_back("jcbb_nodes", static_cast<double>(filter_.jcbbNodes()));
	return c;
}

}  // namespace esif
