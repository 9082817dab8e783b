#include "DivergenceGuard.h"

#include <esif/core/Errors.h>

#include <cmath>
#include <sstream>

namespace esif::dslam
{
void DivergenceGuard::travel(const OdometryIncrement& u)
{
	const double d = std::hypot(u.delta.x(), u.delta.y());
	if (std::isfinite(d)) path_m_ += d;
}

void DivergenceGuard::sense(const Scan& scan)
{
	for (const auto& m : scan.measurements)
		if (std::isfinite(m.range_m) && m.range_m > max_range_m_) max_range_m_ = m.range_m;
}

void DivergenceGuard::check(const std::vector<LandmarkId>& ids, const Eigen::VectorXd& positions,
							const Pose2& robot) const
{
	if (!robot.allFinite()) throw NumericalError("D-SLAM diverged: the robot pose estimate is not finite");
	const double limit = bound();
	for (std::size_t i = 0; i < ids.size(); ++i)
	{
		const Eigen::Vector2d p = positions.segment<2>(2 * static_cast<Eigen::Index>(i));
		if (!p.allFinite())
			throw NumericalError("D-SLAM diverged: feature " + std::to_string(ids[i]) + " estimate is not finite");
		if (factor_ > 0 && p.norm() > limit)
		{
			std::ostringstream msg;
			msg.precision(4);
			msg << "D-SLAM diverged: feature " << ids[i] << " estimated " << p.norm()
				<< " m from the map origin, beyond " << factor_ << " x (path " << path_m_ << " m + range "
				<< max_range_m_ << " m) (see [dslam] divergence_factor)";
			throw NumericalError(msg.str());
		}
	}
}

void DivergenceGuard::fusion(bool agreed)
{
	disagreeing_in_a_row_ = agreed ? 0 : disagreeing_in_a_row_ + 1;
	if (max_disagreeing_scans_ > 0 && disagreeing_in_a_row_ >= max_disagreeing_scans_)
		throw NumericalError("D-SLAM diverged: the map and the local SLAM disagreed on the robot pose at " +
							 std::to_string(disagreeing_in_a_row_) +
							 " admissible scans in a row (see [dslam] divergence_disagreeing_scans)");
}

}  // namespace esif::dslam
