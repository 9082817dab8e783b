#pragma once
/// \file ReferencePair.h
/// Choice of D-SLAM's two reference features f1, f2 among the previously
/// mapped features of a scan (book Sec. 3.1.1.2: "the reference points can
/// be any two features, which have been previously observed"). Serves D-SLAM
/// (Ch. 3) and D-SLAM map joining (Ch. 4), which recasts local maps relative
/// to a pair chosen the same way.
///
/// Why the choice matters: z_new is a one-to-one function of z_old for any
/// pair, so in the linear approximation every pair carries the same map
/// information. It matters for the linearisation: all angles a_i12 are
/// measured from the baseline f1 -> f2, whose direction is known only to
/// about sigma_tangential / d12, and z_rob (eq. 3.18) degenerates when the
/// robot is nearly in line with f1 and f2 (a thin triangle robot-f1-f2).
/// So the default picks the longest baseline among pairs that subtend a
/// fair angle at the robot, and rejects pairs that are nearly co-located.

#include <Eigen/Core>
#include <optional>
#include <utility>
#include <vector>

namespace esif::relative
{
enum class ReferencePolicy
{
	Widest,		 ///< longest baseline among well-conditioned pairs (default)
	FirstMapped	 ///< the two earliest mapped features, as in the book's presentation
};

struct ReferenceRules
{
	ReferencePolicy policy = ReferencePolicy::Widest;
	double min_separation_m = 0.5;	///< |f1 - f2| at least this
	double min_angle_rad = 0.0873;	///< angle f1-robot-f2 in [this, pi - this] (5 deg)
};

/// A candidate: its point in the robot frame and when it was mapped.
struct ReferenceCandidate
{
	Eigen::Vector2d point;
	long mapped_order = 0;  ///< smaller = mapped earlier
};

/// Indices (into `candidates`) of f1, f2; none when no pair satisfies the
/// rules (the scan is then treated as not admissible).
std::optional<std::pair<int, int>> chooseReferencePair(const std::vector<ReferenceCandidate>& candidates,
													   const ReferenceRules& rules);

}  // namespace esif::relative
