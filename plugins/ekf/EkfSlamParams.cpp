#include "EkfSlamParams.h"

namespace esif
{
void EkfSlamParams::declare(ParamBinder& b)
{
	association.declare(b);
	association.declareMerging(b);
	b.enumeration<JacobianPoints>(
		"jacobians", jacobians,
		{{"current", JacobianPoints::Current}, {"first_estimates", JacobianPoints::FirstEstimates}},
		"where the EKF takes its Jacobians: current = at the latest estimate (textbook EKF); first_estimates = "
		"at the robot's prior and each landmark's first estimate (Huang et al.'s FEJ: the global rotation stays "
		"unobservable)");
}

}  // namespace esif
