#include "HeldFeatureTracking.h"

#include <esif/association/DataAssociation.h>

#include <limits>

namespace esif::dslam
{
std::vector<TrackedMeasurement> trackHeldFeatures(const LocalSlam& local, const Scan& scan, bool jcbb,
												  double gate_quantile, const CandidateWindow& window,
												  const SearchBounds& bounds)
{
	const auto& ms = scan.measurements;
	std::vector<TrackedMeasurement> out(ms.size(), {std::nullopt, std::numeric_limits<double>::infinity()});
	if (ms.empty() || local.order().empty()) return out;

	std::vector<std::size_t> candidates;
	for (std::size_t k = 0; k < local.order().size(); ++k)
		if (window.admits(local.predictHeldMeasurement(k, scan.sensor_on_robot))) candidates.push_back(k);
	if (candidates.empty()) return out;

	// One noise for all, as the map-level association (RelativeAssociation):
	// a scan's measurements share their sensor's covariance.
	const LocalSlam::HeldPrediction held =
		local.predictHeld(candidates, scan.sensor_on_robot, sightingCov(scan, ms.front()));
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
		out[i].min_distance2 = r.min_distance2[i];
		const int c = r.candidate_of[i];
		if (c < 0 || taken[static_cast<std::size_t>(c)]) continue;
		taken[static_cast<std::size_t>(c)] = true;
		out[i].feature = local.order()[candidates[static_cast<std::size_t>(c)]];
	}
	return out;
}

}  // namespace esif::dslam
