#pragma once
/// \file SuspectResult.h
/// A run that finished but whose result nobody should use without a look:
/// it maps no landmark; a map-joining run fused no local map; with the true
/// landmark of each measurement known, it matched none of more measurements
/// than there are true landmarks, or mapped more than three landmarks per
/// true one; given landmark IDs, it rejected more than a quarter of those
/// measurements; it rejected more measurements than it used; or, with
/// ground truth, its landmarks' mean NEES is above 100. Each rule
/// is explained in SuspectResult.cpp. Such a run is not a failure (it exits
/// 0 and writes every output), but it is never silent either: one warning
/// line, `suspect` and `suspect_reason` in stats.json, a `suspect` status in
/// `esif compare` and a line in a Monte Carlo summary.

#include <esif/formats/StatsJson.h>

#include <optional>
#include <string>

namespace esif
{
/// What makes the run of `stats` suspect, naming the counts; nullopt when nothing does.
std::optional<std::string> suspectReason(const Stats& stats);

/// Sets "suspect" (0 or 1) and "suspect_reason" (text, or null) in `stats`
/// from suspectReason; returns the reason.
std::optional<std::string> markSuspect(Stats& stats);

/// The reason a finished run's stats.json gives, nullopt when it is not suspect.
std::optional<std::string> recordedSuspectReason(const Stats& stats);

}  // namespace esif
