#include "MeasurementOutliers.h"

#include <esif/models/Se2.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace esif
{
MeasurementOutliers::MeasurementOutliers(
	const Scenario& scenario, std::vector<Eigen::Vector2d> landmarks, std::vector<LandmarkId> landmark_ids,
	std::uint32_t seed)
	: s_(scenario),
	  landmarks_(std::move(landmarks)),
	  landmark_ids_(std::move(landmark_ids)),
	  rng_(seed),
	  next_clutter_id_(scenario.clutterIdBase())
{
}

void MeasurementOutliers::apply(
	Scan& scan, std::vector<std::optional<LandmarkId>>& true_ids, const Eigen::Matrix2d& measurement_cov)
{
	if (s_.wrong_id_rate > 0) misreadIds(scan, true_ids);
	if (s_.spurious_rate > 0) addClutter(scan, true_ids, measurement_cov);
}

void MeasurementOutliers::misreadIds(Scan& scan, const std::vector<std::optional<LandmarkId>>& true_ids)
{
	std::bernoulli_distribution misread(s_.wrong_id_rate);
	// IDs the scan holds or stands for: its landmarks and the misreads so far.
	std::set<LandmarkId> taken;
	for (const auto& id : true_ids) taken.insert(*id);
	for (std::size_t i = 0; i < scan.measurements.size(); ++i)
	{
		if (!misread(rng_)) continue;
		const LandmarkId wrong = otherLandmark(*true_ids[i], taken);
		if (wrong == *true_ids[i]) continue;
		scan.measurements[i].id = wrong;
		taken.insert(wrong);
		++wrong_ids_;
	}
}

/// A misread gives the ID of a neighbour of the true landmark (a beacon
/// read as one next to it): uniformly one of the kMisreadNeighbours
/// landmarks nearest to it, among those the scan neither measures nor
/// already names (`taken`), since a scan cannot hold one ID twice (MRPT's CObservationBearingRange
/// refuses to store it). The neighbours are mostly just out of view, so a
/// filter's visibility check rarely rules the wrong landmark out.
LandmarkId MeasurementOutliers::otherLandmark(LandmarkId true_id, const std::set<LandmarkId>& taken)
{
	const auto self = std::find(landmark_ids_.begin(), landmark_ids_.end(), true_id);
	const Eigen::Vector2d at = landmarks_[static_cast<std::size_t>(self - landmark_ids_.begin())];
	std::vector<std::pair<double, LandmarkId>> candidates;
	for (std::size_t j = 0; j < landmark_ids_.size(); ++j)
		if (!taken.count(landmark_ids_[j]))
			candidates.emplace_back((landmarks_[j] - at).squaredNorm(), landmark_ids_[j]);
	if (candidates.empty()) return true_id;	 // every landmark is in this scan: no ID left to give
	const std::size_t n = std::min(kMisreadNeighbours, candidates.size());
	std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(n), candidates.end());
	return candidates[std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_)].second;
}

/// Clutter uniform over the sensed area: a range with density proportional
/// to r (r = R sqrt(u)) and a uniform bearing across the field of view.
void MeasurementOutliers::addClutter(
	Scan& scan, std::vector<std::optional<LandmarkId>>& true_ids, const Eigen::Matrix2d& cov)
{
	const int count = std::poisson_distribution<int>(s_.spurious_rate)(rng_);
	const double half_fov = s_.sensor_fov_deg * M_PI / 180.0 / 2;
	std::uniform_real_distribution<double> unit(0.0, 1.0), bearing(-half_fov, half_fov);
	for (int c = 0; c < count; ++c)
	{
		RangeBearing m;
		m.range_m = s_.sensor_max_range_m * std::sqrt(unit(rng_));
		m.bearing_rad = wrapAngle(bearing(rng_));
		m.cov = cov;
		m.id = next_clutter_id_++;
		// At a random place: a filter cannot tell clutter by its position in the scan.
		const auto at = std::uniform_int_distribution<std::size_t>(0, scan.measurements.size())(rng_);
		scan.measurements.insert(scan.measurements.begin() + static_cast<std::ptrdiff_t>(at), m);
		true_ids.insert(true_ids.begin() + static_cast<std::ptrdiff_t>(at), std::nullopt);
		++spurious_;
	}
}

}  // namespace esif
