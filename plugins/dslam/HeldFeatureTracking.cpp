#include "HeldFeatureTracking.h"

#include <esif/association/DataAssociation.h>
#include <esif/models/Se2.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <limits>

namespace esif::dslam
{
namespace
{
/// One look at every held feature for a scan: which are candidates, and
/// each measurement's smallest squared Mahalanobis distance to any held
/// feature, in view or not (noise `R` added to each H P H^T).
struct HeldFeaturesSeen
{
	std::vector<std::size_t> candidates;  ///< held indices `window` admits
	std::vector<double> nearest;  ///< per measurement
};

HeldFeaturesSeen lookAtHeldFeatures(const LocalSlam& local, const Scan& scan, const Eigen::Matrix2d& R,
									const CandidateWindow& window)
{
	const auto& ms = scan.measurements;
	HeldFeaturesSeen out;
	out.nearest.assign(ms.size(), std::numeric_limits<double>::infinity());
	for (std::size_t k = 0; k < local.order().size(); ++k)
	{
		const LocalSlam::FeaturePrediction h = local.predictHeldFeature(k, scan.sensor_on_robot);
		if (window.admits(h.z)) out.candidates.push_back(k);
		const Eigen::LDLT<Eigen::Matrix2d> S(h.covariance + R);
		for (std::size_t i = 0; i < ms.size(); ++i)
		{
			Eigen::Vector2d nu(ms[i].range_m - h.z(0), wrapAngle(ms[i].bearing_rad - h.z(1)));
			out.nearest[i] = std::min(out.nearest[i], nu.dot(S.solve(nu)));
		}
	}
	return out;
}
}  // namespace

std::vector<TrackedMeasurement> trackHeldFeatures(const LocalSlam& local, const Scan& scan, bool jcbb,
												  double gate_quantile, const CandidateWindow& window,
												  const SearchBounds& bounds)
{
	const auto& ms = scan.measurements;
	std::vector<TrackedMeasurement> out(ms.size(), {std::nullopt, std::numeric_limits<double>::infinity()});
	if (ms.empty() || local.order().empty()) return out;

	// One noise for all, as the map-level association (RelativeAssociation):
	// a scan's measurements share their sensor's covariance.
	const Eigen::Matrix2d R = sightingCov(scan, ms.front());
	// Held features out of view are no candidates, but a measurement close to
	// one is not a new feature either (Dslam's ambiguity rule).
	const HeldFeaturesSeen seen = lookAtHeldFeatures(local, scan, R, window);
	for (std::size_t i = 0; i < ms.size(); ++i) out[i].min_distance2 = seen.nearest[i];
	const std::vector<std::size_t>& candidates = seen.candidates;
	if (candidates.empty()) return out;
	const LocalSlam::HeldPrediction held = local.predictHeld(candidates, scan.sensor_on_robot, R);
	AssociationInput in;
	in.observations.resize(static_cast<Eigen::Index>(ms.size()), 2);
	for (std::size_t i = 0; i < ms.size(); ++i) in.observations.row(static_cast<Eigen::Index>(i)) << ms[i].range_m, ms[i].bearing_rad;
	in.predictions = held.predictions;
	in.covariance = held.covariance;
	const AssociationResult r =
		associate(in, jcbb ? AssociationMethod::Jcbb : AssociationMethod::NearestNeighbor, gate_quantile, bounds);

	std::vector<bool> taken(candidates.size(), false);
	for (std::size_t i = 0; i < ms.size(); ++i)
	{
		const int c = r.candidate_of[i];
		if (c < 0 || taken[static_cast<std::size_t>(c)]) continue;
		taken[static_cast<std::size_t>(c)] = true;
		out[i].feature = local.order()[candidates[static_cast<std::size_t>(c)]];
	}
	return out;
}

}  // namespace esif::dslam
