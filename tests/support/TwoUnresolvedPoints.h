#pragma once
/// \file TwoUnresolvedPoints.h
/// A constructed log for landmark merging (ekf/CoincidentLandmarks.h),
/// shared by the SDK's and the EKF plugin's tests: a robot standing still
/// that sees two points 0.15 m apart along one bearing, at 3.0 and 3.15 m,
/// with 0.3 m range noise, so a few sightings cannot resolve them.

#include <esif/core/StepInput.h>

#include <cmath>
#include <cstddef>

namespace esif::test
{
/// Step k: no odometry at k = 0, then a standstill with negligible noise;
/// both points seen, without IDs.
inline StepInput standingBesideTwoUnresolvedPoints(std::size_t k)
{
	StepInput s;
	s.index = k;
	if (k > 0) s.odometry = OdometryIncrement{{0, 0, 0}, Eigen::Vector3d(1e-6, 1e-6, 1e-8).asDiagonal()};
	Scan scan;
	for (const double range : {3.0, 3.15})
	{
		RangeBearing m;
		m.range_m = range;
		m.cov = Eigen::Vector2d(0.09, std::pow(M_PI / 180, 2)).asDiagonal();
		scan.measurements.push_back(m);
	}
	s.scan = scan;
	return s;
}

}  // namespace esif::test
