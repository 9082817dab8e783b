#pragma once
/// \file LandmarkSetDistance.h
/// Two maps compared as sets of points, with no identity known on either
/// side: the OSPA distance (Schuhmacher, Vo and Vo, "A consistent metric
/// for performance evaluation of multi-object filters", IEEE Trans. Signal
/// Processing 56(8), 2008) and the optimal one-to-one pairing behind it.
/// For sets X (m points) and Y (n points), m <= n,
///
///     d_c^p(X, Y) = ( ( min over assignments a of sum_i min(c, |x_i - y_a(i)|)^p
///                       + c^p (n - m) ) / n )^(1/p),
///
/// 0 when both are empty. The cut-off c is what one landmark can cost at
/// most: an estimate c or more from every true landmark is as wrong as a
/// missing or an extra one. esif uses p = 2 (kOspaOrder): with as many
/// estimates as true landmarks and every error below c, OSPA is then the
/// RMS error of the optimally paired landmarks, the same figure as
/// landmark_rmse_m and ref_landmark_rms_m, so the three read alike; every
/// missing, extra or far landmark adds c^2 / n to the mean square.
///
/// Only pairs closer than c can lower the cost, so the assignment is solved
/// separately on each group of points linked by such pairs
/// (OptimalAssignment.h): exact, and small problems however large the maps.
/// The pairs are found in cells of side c, in time linear in the maps.

#include <esif/core/Estimate.h>

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

namespace esif
{
/// OSPA order p of every figure esif reports.
inline constexpr double kOspaOrder = 2.0;

struct SetMatch
{
	double ospa = 0;  ///< d_c^p(X, Y)
	/// The optimal assignment's pairs closer than c: (index in X, index in Y).
	std::vector<std::pair<std::size_t, std::size_t>> pairs;
};

/// The positions of `landmarks`, in their order: a map as a point set.
std::vector<Eigen::Vector2d> landmarkPositions(const std::vector<LandmarkEstimate>& landmarks);

/// OSPA of `x` and `y` with cut-off `c` > 0 and order `p` >= 1
/// (std::invalid_argument otherwise), and the pairs closer than c. A point
/// that is not finite (a diverged landmark) is paired with nothing.
SetMatch matchPointSets(const std::vector<Eigen::Vector2d>& x, const std::vector<Eigen::Vector2d>& y, double c,
						double p = kOspaOrder);

}  // namespace esif
