#pragma once
/// \file SightingRejections.h
/// Why a LandmarkEkf associating by distance left sightings out of its
/// update: the causes behind stats.json's da_rejected, which the EKF plugin
/// reports as they are and the map-joining plugins summed over their local
/// maps. Without IDs on MRCLAM a quarter to a half of all sightings are
/// rejected; these counts say which rule did it.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace esif
{
struct SightingRejections
{
	/// Matched, but another landmark was nearly as likely (Ambiguity.h): the
	/// sighting waits.
	std::size_t ambiguous_waits = 0;
	/// Matched no landmark, yet inside some landmark's new-landmark gate:
	/// neither it nor new (the authors' "poor observation").
	std::size_t poorly_observed = 0;
	/// First sightings of a landmark not in the map, held as tentative and
	/// not fused (TentativeFeatures.h): confirmed or not, they are not used.
	std::size_t unconfirmed = 0;

	SightingRejections& operator+=(const SightingRejections& other);
	/// Appends <prefix>ambiguous_waits, <prefix>poorly_observed_sightings and
	/// <prefix>unconfirmed_sightings.
	void appendCounters(std::vector<std::pair<std::string, double>>& counters, const std::string& prefix) const;
};

}  // namespace esif
