#include <esif/association/CandidateWindow.h>

#include <cmath>
#include <limits>

namespace esif
{
CandidateWindow::CandidateWindow(const Scan& scan, double margin_m, double margin_deg)
	: max_range_m_(scan.max_range_m > 0 ? scan.max_range_m + margin_m : std::numeric_limits<double>::infinity()),
	  half_fov_rad_(scan.fov_rad > 0 ? 0.5 * scan.fov_rad + margin_deg * (M_PI / 180.0)
									 : std::numeric_limits<double>::infinity()),
	  near_m_(margin_m)
{
}

bool CandidateWindow::admits(const Eigen::Vector2d& range_bearing, const Eigen::Vector2d& widen) const
{
	if (range_bearing(0) <= near_m_) return true;
	return range_bearing(0) <= max_range_m_ + widen(0) && std::abs(range_bearing(1)) <= half_fov_rad_ + widen(1);
}

}  // namespace esif
