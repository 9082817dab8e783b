#include "SolveSchedule.h"

#include <algorithm>
#include <cmath>

namespace esif::ceres_full
{
SolveSchedule::SolveSchedule(double growth, std::size_t min_new_poses, std::size_t every_steps)
	: growth_(growth), min_new_poses_(std::max<std::size_t>(1, min_new_poses)), every_steps_(every_steps)
{
}

bool SolveSchedule::due(std::size_t steps, std::size_t poses) const
{
	if (every_steps_ > 0 && steps > 0 && steps % every_steps_ == 0) return true;
	if (growth_ <= 0 || poses <= poses_at_last_solve_) return false;
	const auto grown = static_cast<std::size_t>(std::ceil(growth_ * static_cast<double>(poses_at_last_solve_)));
	return poses - poses_at_last_solve_ >= std::max(min_new_poses_, grown);
}

}  // namespace esif::ceres_full
