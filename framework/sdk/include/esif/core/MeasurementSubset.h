#pragma once
/// \file MeasurementSubset.h
/// Part of one scan's measurements, processed on its own and reported on the
/// whole scan: the part keeps the scan's sensor, field of view and sighting
/// noise, and every measurement left out is reported Rejected (id -1) in its
/// place. LandmarkEkf leaves out the measurements nearer than its minimum
/// range this way, the local-map builder those its association filter left
/// out (LocalMapBuilder.h).

#include <esif/core/Estimate.h>
#include <esif/core/StepInput.h>

#include <cstddef>
#include <functional>
#include <vector>

namespace esif
{
struct MeasurementSubset
{
	Scan scan;	///< the whole scan with only the kept measurements
	std::vector<std::size_t> kept;	///< their indices in the whole scan, in order
	std::size_t whole = 0;	///< measurements of the whole scan

	/// `on_part` (one Association per kept measurement) spread over the whole
	/// scan, Rejected (id -1) where a measurement was left out.
	StepReport spread(const StepReport& on_part) const;
};

/// The measurements `m` (index `i`) of `scan` for which keep(i, m) holds.
MeasurementSubset measurementSubset(
	const Scan& scan, const std::function<bool(std::size_t i, const RangeBearing& m)>& keep);

}  // namespace esif
