#pragma once
/// \file SolutionChecks.h
/// Checks of a converged full-SLAM solution that Ceres' convergence test
/// cannot make: a pose collapsed onto a landmark it measured metres away
/// (the range term's gradient vanishes there and its bearing term is
/// undefined, so the solver can stop on it; J is then rank deficient), and
/// a cost far above its chi-square expectation (a local minimum, or a noise
/// model or association that does not fit the data).

#include "FullSlamGraph.h"

#include <cstddef>
#include <string>

namespace esif::ceres_full
{
/// Range excess [standard deviations] beyond which a measurement cannot have
/// been taken from that close: 5 sigma is a 6e-7 chance for Gaussian noise.
constexpr double kDegenerateRangeSigmas = 5.0;

/// Number of distinct poses whose sensor lies within `distance_m` of a
/// landmark that the pose measured more than kDegenerateRangeSigmas range
/// standard deviations further away. (A robot may pass close to a feature;
/// its measurement is then close too, within the noise.)
std::size_t countDegeneratePoses(const FullSlamGraph& graph, double distance_m);

struct SolutionCheck
{
	double chi2 = 0;  ///< plain sum of squared whitened residuals
	double dof = 0;	 ///< residuals - estimated parameters
	std::size_t degenerate_poses = 0;
	/// Measurements beyond the outlier gate when they were too many to drop (0: none or dropped).
	std::size_t excess_outliers = 0;
	bool plausible = true;

	/// chi2 / dof; NaN when the problem has no redundancy (dof <= 0).
	double chi2PerDof() const;
	/// One line for stderr naming what is wrong, empty when plausible.
	std::string warning(double max_chi2_per_dof) const;
};

/// Judges a solution: implausible when a pose is degenerate, chi2 / dof
/// exceeds `max_chi2_per_dof` or too many measurements lie beyond the
/// outlier gate to be outliers.
SolutionCheck checkSolution(
	double chi2, double dof, std::size_t degenerate_poses, double max_chi2_per_dof, std::size_t excess_outliers = 0);

}  // namespace esif::ceres_full
