#pragma once
/// \file ReferenceChoice.h
/// The two reference features of a local map (book Sec. 4.2.2: any two
/// features already in the global map): the framework's widest-baseline
/// choice (relative::chooseReferencePair) among the eligible features, with
/// the robot-angle rule of D-SLAM's scans replaced by a clearance rule, since
/// in a local map no robot sits at the origin but a feature close to f1
/// makes its angle alpha_i12 undefined.

#include <Eigen/Core>
#include <optional>
#include <utility>
#include <vector>

namespace esif::lmj
{
/// Indices (into `points`) of f1 and f2 among `eligible`: at least
/// `min_separation_m` apart, and no other point of `points` within
/// `min_clearance_m` of either; the widest such pair. nullopt when none.
std::optional<std::pair<int, int>> chooseReferenceFeatures(
	const std::vector<Eigen::Vector2d>& points, const std::vector<int>& eligible, double min_separation_m,
	double min_clearance_m);

}  // namespace esif::lmj
