/// \file SuspectResult.cpp
/// When a finished run is suspect; see SuspectResult.h.

#include <esif/eval/SuspectResult.h>

namespace esif
{
std::optional<std::string> suspectReason(const Stats& stats)
{
	const auto landmarks = stats.number("landmarks");
	if (landmarks && *landmarks == 0) return std::string("it mapped no landmark");
	const auto fused = stats.number("plugin_local_maps_fused");
	const auto maps = stats.number("local_maps");
	if (fused && *fused == 0)
		return "it fused no local map" + (maps ? " (of " + std::to_string(static_cast<long long>(*maps)) + ")" : "");
	const double rejected = stats.number("da_rejected").value_or(0);
	const double used = stats.number("da_new").value_or(0) + stats.number("da_matched").value_or(0);
	if (rejected > used)
		return "it rejected " + std::to_string(static_cast<long long>(rejected)) + " of " +
			   std::to_string(static_cast<long long>(rejected + used)) + " measurements";
	return std::nullopt;
}

std::optional<std::string> markSuspect(Stats& stats)
{
	const auto reason = suspectReason(stats);
	stats.set("suspect", StatValue(reason ? 1LL : 0LL));
	stats.set("suspect_reason", reason ? StatValue(*reason) : StatValue(nullptr));
	return reason;
}

std::optional<std::string> recordedSuspectReason(const Stats& stats)
{
	if (stats.number("suspect").value_or(0) == 0) return std::nullopt;
	return stats.text("suspect_reason").value_or("suspect");
}

}  // namespace esif
