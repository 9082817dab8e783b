#pragma once
/// \file ReferenceChoice.h
/// The two reference features of a local map (book Sec. 4.2.2: any two
/// features already in the global map): the widest baseline among the
/// eligible features, with the robot-angle rule of D-SLAM's scans replaced by
/// a clearance rule on f1, since in a local map no robot sits at the origin
/// but a feature close to f1 makes its angle alpha_i12 (and distance d_1i)
/// ill-conditioned (shared/design/DSLAM-LMJ.md). The rule is on f1 only: f2
/// enters every alpha_i12 through d12, at least min_separation_m.

#include <Eigen/Core>
#include <optional>
#include <utility>
#include <vector>

namespace esif::lmj
{
/// Indices (into `points`) of f1 and f2 among `eligible`, at least
/// `min_separation_m` apart: the widest such pair whose f1 has no other
/// point of `points` within `min_clearance_m` (f1 the earlier of the two in
/// `eligible` when both are clear); when no f1 is that clear, the pair with
/// the clearest f1 (landmarks in pairs 0.17-0.21 m apart, as MRCLAM's
/// cylinders, would otherwise leave a map unjoinable). nullopt when no two
/// eligible points are far enough apart.
std::optional<std::pair<int, int>> chooseReferenceFeatures(
	const std::vector<Eigen::Vector2d>& points, const std::vector<int>& eligible, double min_separation_m,
	double min_clearance_m);

}  // namespace esif::lmj
