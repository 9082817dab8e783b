#pragma once
/// \file EkfSlamParams.h
/// The [ekf] section of the EKF plugin: the association and update keys
/// every LandmarkEkf shares (EkfAssociationParams) and where this filter
/// takes its Jacobians.

#include <esif/config/ParamBinder.h>
#include <esif/ekf/EkfAssociationParams.h>
#include <esif/ekf/EkfSlamCore.h>

namespace esif
{
struct EkfSlamParams
{
	EkfAssociationParams association;
	/// current = the textbook EKF; first_estimates = first-estimates
	/// Jacobians (JacobianPoints in EkfSlamCore.h).
	JacobianPoints jacobians = JacobianPoints::Current;

	void declare(ParamBinder& b);
};

}  // namespace esif
