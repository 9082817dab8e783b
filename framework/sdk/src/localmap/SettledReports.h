#pragma once
/// \file SettledReports.h
/// A map-joining filter decides which global landmark a measurement is only
/// when the measurement's local map is fused. This turns the reports the
/// local-map builder gave at each step (by the local map's feature IDs) into
/// final ones (FilterPlugin::finalReports): each measurement of a feature
/// the fusion kept names its global landmark, New for the first measurement
/// of that landmark in the whole run, Matched after; a measurement of a
/// feature the fusion left out, or that the builder rejected, is Rejected.

#include <esif/core/Estimate.h>

#include <set>
#include <vector>

namespace esif
{
/// Appends to `out` the settled reports of one fused map: `step_reports`
/// (its steps, by local IDs), `local_ids` its features and `decisions` the
/// fusion's decision for each (Matched/New with the global ID, or
/// Rejected). `started` holds the global landmarks already reported New.
void appendSettledReports(const std::vector<StepReport>& step_reports, const std::vector<LandmarkId>& local_ids,
						  const StepReport& decisions, std::set<LandmarkId>& started, std::vector<StepReport>& out);

}  // namespace esif
