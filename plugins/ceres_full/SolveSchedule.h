#pragma once
/// \file SolveSchedule.h
/// When to re-solve the full-SLAM problem during a run. Between solves new
/// poses are warm-started from odometry composed onto the current estimate;
/// a re-solve pulls that estimate back to the optimum so far, so the next
/// poses start inside its basin. Re-solving whenever the pose count has grown
/// by a fixed fraction g makes the solve sizes a geometric series, whose sum
/// is (1 + 1/g) times the final size: the work grows about linearly with the
/// run, unlike re-solving every K steps (N / K solves of up to N poses).

#include <cstddef>

namespace esif::ceres_full
{
class SolveSchedule
{
   public:
	/// `growth` = 0 disables the growth rule, `every_steps` = 0 the fixed one.
	SolveSchedule(double growth, std::size_t min_new_poses, std::size_t every_steps);

	/// True when a re-solve is due after `steps` steps with `poses` poses.
	bool due(std::size_t steps, std::size_t poses) const;
	/// Records a solve of `poses` poses.
	void solved(std::size_t poses) { poses_at_last_solve_ = poses; }

   private:
	double growth_;
	std::size_t min_new_poses_;
	std::size_t every_steps_;
	std::size_t poses_at_last_solve_ = 0;
};

}  // namespace esif::ceres_full
