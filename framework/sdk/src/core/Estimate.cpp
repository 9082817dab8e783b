#include <esif/core/Estimate.h>

namespace esif
{
const char* formulationName(Formulation f)
{
	switch (f)
	{
		case Formulation::EkfSlam: return "ekf_slam";
		case Formulation::FullSlamOptimum: return "full_slam";
		case Formulation::Dslam: return "dslam";
		case Formulation::DslamLocalMapJoining: return "dslam_local_map_joining";
		case Formulation::Slsjf: return "slsjf";
		case Formulation::Other: break;
	}
	return "other";
}

}  // namespace esif
