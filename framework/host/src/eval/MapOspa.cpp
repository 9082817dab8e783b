/// \file MapOspa.cpp
/// The OSPA cut-off of a rawlog and a final map's OSPA to the truth; see MapOspa.h.

#include <esif/association/Chi2.h>
#include <esif/eval/LandmarkSetDistance.h>
#include <esif/eval/MapOspa.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace esif
{
namespace
{
/// Standard deviation of a range-bearing measurement's position along the
/// major axis of its covariance: the position is r (cos b, sin b), so its
/// covariance is a rotation of D C D with D = diag(1, r), C over (range, bearing).
double largestPositionSigma(const RangeBearing& m)
{
	const Eigen::DiagonalMatrix<double, 2> d(1.0, m.range_m);
	const Eigen::Matrix2d position = d * m.cov * d;
	const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(position, Eigen::EigenvaluesOnly);
	return std::sqrt(std::max(0.0, eigen.eigenvalues()(1)));
}
}  // namespace

std::optional<double> ospaCutoff(const std::vector<StepInput>& steps)
{
	OspaCutoff cutoff;
	for (const StepInput& step : steps) cutoff.add(step);
	return cutoff.value();
}

void OspaCutoff::add(const StepInput& step)
{
	if (step.scan)
		for (const RangeBearing& m : step.scan->measurements) sigmas_.push_back(largestPositionSigma(m));
}

std::optional<double> OspaCutoff::value() const
{
	if (sigmas_.empty()) return std::nullopt;
	std::vector<double> sigmas = sigmas_;
	const auto middle = sigmas.begin() + static_cast<std::ptrdiff_t>(sigmas.size() / 2);
	std::nth_element(sigmas.begin(), middle, sigmas.end());
	static const double gate_sigmas = std::sqrt(chi2Quantile(0.9999, 2));
	return gate_sigmas * *middle;
}

double truthOspa(const GroundTruth& truth, const Estimate& estimate, const std::set<LandmarkId>& observed, double c)
{
	std::vector<Eigen::Vector2d> actual;
	for (const auto& [id, position] : truth.landmarks)
		if (observed.empty() || observed.count(id)) actual.push_back(position);
	return matchPointSets(landmarkPositions(estimate.landmarks), actual, c).ospa;
}

}  // namespace esif
