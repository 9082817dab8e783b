#pragma once
/// \file Ambiguity.h
/// When a match should wait: one observation, several candidates nearly as
/// likely. Nearest neighbour and JCBB always pick one; after a long blind
/// drive the robot's uncertainty makes several landmarks compatible with a
/// measurement, and a scan holding one landmark gives JCBB nothing to
/// decide with, so the pick is a coin toss that the update then makes
/// permanent. Waiting (leaving the measurement out) costs one measurement;
/// the next scan, or the next landmark in view, resolves the pose.
///
/// Two candidates the sensor itself cannot tell apart (their predicted
/// observations closer than the margin in the sensor's own noise: twin
/// trees, cylinders 0.2 m apart) are not such an ambiguity: no wait resolves
/// them, and either pick moves the estimate alike.

#include <Eigen/Core>
#include <functional>

namespace esif
{
/// The squared Mahalanobis distance by which every other candidate must be
/// less likely than the chosen one: the chi-square quantile `quantile` of 2
/// degrees of freedom (0.99: a likelihood ratio of 100); 0 turns the test off.
double ambiguityMarginDistance2(double quantile);

/// Whether matching an observation to candidate `chosen` is ambiguous:
/// another candidate j has d2(j) < d2(chosen) + margin_d2 while
/// sensor_separation_d2(j), the squared distance between the predicted
/// observations of j and of `chosen` in the sensor's own noise, is at least
/// margin_d2. False when margin_d2 <= 0.
bool ambiguousMatch(const Eigen::VectorXd& d2, Eigen::Index chosen, double margin_d2,
					const std::function<double(Eigen::Index)>& sensor_separation_d2);

}  // namespace esif
