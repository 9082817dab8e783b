#pragma once
/// \file LocalMapMerge.h
/// Two consecutive local maps joined into one through the pose they share
/// (the end pose of the first, which is the start pose of the second): the
/// fallback of the D-SLAM map-joining filter for a map that shares fewer than
/// two features with the global map (book Sec. 4.4.4; the authors' Linear
/// SLAM code "absorbs" such a map by pose-feature joining, see
/// DSLAM-LMJ.md §9). The maths is one SLSJF step (book Ch. 5, eq. 5.4-5.9)
/// with the first map as the global map, solved to convergence by
/// Gauss-Newton, after which the shared pose is marginalised out.

#include <esif/localmap/LocalMap.h>

namespace esif
{
/// Map `a` (index k) followed by map `b` (index k+1, expressed in a's end pose, or linked to it by b.link)
/// joined into one local map in a's frame: its end pose is b's end pose, its features the union (a feature
/// in both, by ID, is one feature estimated from both), index a.index, steps/measurements/step_reports
/// concatenated, first_step of a, last_step of b, in_earlier_maps from a (and b's own for features only in b),
/// ids_identify_features = a's && b's. Throws NumericalError naming both maps if the result is not SPD.
///
/// Variables: e_a (a's end pose), s (b's start pose, only when b.link is set),
/// e_b (b's end pose) and the union of the features, all in a's frame.
/// Terms:
///  - map a: a prior on [e_a; features of a] with information a.information
///    (a's start pose is the origin of the frame, a constant);
///  - the link (eq. 5.4-5.6): the odometry u = b.link->delta measures s in
///    the frame of e_a, u = e_a^-1 (+) s + v, v ~ N(0, Q = b.link->cov), Q
///    being over (dx, dy, dphi) of the increment as everywhere in esif; to
///    first order s = e_a (+) u + w with w's covariance Q rotated into a's
///    frame (eq. 5.4's w);
///  - map b: the virtual observation of eq. 5.8 from s (or e_a) of
///    [e_b; features of b], with information b.information (eq. 5.9).
/// The least-squares problem is solved by Gauss-Newton (dense; at most
/// kMergeMaxIterations iterations, until no variable moves more than
/// kMergeTolerance), then e_a and s are marginalised out of the information
/// matrix by a Schur complement. The result's covariance is set (the
/// inverse of its information, by a Cholesky solve) and its link is a's.
///
/// Throws std::invalid_argument when b.index != a.index + 1 or when a map's
/// information matrix does not match its state size; NumericalError (naming
/// both maps) when a normal matrix, the marginal information or the result is
/// not symmetric positive definite, or a value is not finite.
LocalMap mergeConsecutiveLocalMaps(const LocalMap& a, const LocalMap& b);

/// Gauss-Newton stops once the largest update of any variable is below this [m, rad].
constexpr double kMergeTolerance = 1e-10;
/// ... or after this many iterations.
constexpr int kMergeMaxIterations = 20;

}  // namespace esif
