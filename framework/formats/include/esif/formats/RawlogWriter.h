#pragma once
/// \file RawlogWriter.h
/// Writes StepInputs as a standard MRPT actions/sensory-frames rawlog (as
/// simul-landmarks does): per step a CActionCollection with one
/// CActionRobotMovement2D, then a CSensoryFrame with one CObservationBearingRange.
/// RawlogReader reads them back step for step.

#include <esif/core/StepInput.h>

#include <mrpt/serialization/CArchive.h>

namespace esif
{
/// The sensor's nominal noise, stored in the observation (validCovariances = false).
struct SensorNoise
{
	double std_range_m = 0.1;
	double std_bearing_rad = 0.0174532925199433;
};

/// Appends one step: its odometry (a zero increment when it has none) with
/// its Gaussian covariance kept exactly, then its scan (an empty one when it
/// has none). Measurements without an ID get INVALID_LANDMARK_ID.
void appendStep(mrpt::serialization::CArchive& archive, const StepInput& step, const SensorNoise& noise);

}  // namespace esif
