/// \file SuspectResult.cpp
/// When a finished run is suspect; see SuspectResult.h.

#include <esif/eval/SuspectResult.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace esif
{
namespace
{
std::string countText(double n) { return std::to_string(static_cast<long long>(n)); }

std::string percentText(double part, double whole) { return countText(std::round(100.0 * part / whole)) + "%"; }

/// Measurements the run used: new or matched.
double usedMeasurements(const Stats& stats)
{
	return stats.number("da_new").value_or(0) + stats.number("da_matched").value_or(0);
}

/// Nothing to judge: no landmark, no local map fused.
std::optional<std::string> emptyResult(const Stats& stats)
{
	const auto landmarks = stats.number("landmarks");
	if (landmarks && *landmarks == 0) return std::string("it mapped no landmark");
	const auto fused = stats.number("plugin_local_maps_fused");
	const auto maps = stats.number("local_maps");
	if (fused && *fused == 0) return "it fused no local map" + (maps ? " (of " + countText(*maps) + ")" : "");
	return std::nullopt;
}

/// More measurements used than true landmarks measured, yet none matched:
/// some true landmark was used twice, so its re-observation started a new
/// landmark instead of updating it (a gate that drops every re-observation).
std::optional<std::string> neverMatched(const Stats& stats)
{
	const auto true_landmarks = stats.number("landmarks_true");
	const double used = usedMeasurements(stats);
	if (!true_landmarks || stats.number("da_matched").value_or(0) != 0 || used <= *true_landmarks)
		return std::nullopt;
	return "it matched none of the " + countText(used) + " measurements it used, which came from " +
		   countText(*true_landmarks) + " true landmarks: every re-observation started a new landmark";
}

/// A map more than kMaxLandmarksPerTrue times the true landmarks measured.
/// Two landmarks within the sensor noise of each other can be merged or
/// split at most in two; more than three per true landmark means landmarks
/// re-created again and again (or mapped clutter).
std::optional<std::string> mapTooLarge(const Stats& stats)
{
	constexpr double kMaxLandmarksPerTrue = 3;
	const auto true_landmarks = stats.number("landmarks_true");
	const auto landmarks = stats.number("landmarks");
	if (!true_landmarks || !landmarks || *landmarks <= kMaxLandmarksPerTrue * *true_landmarks) return std::nullopt;
	return "it mapped " + countText(*landmarks) + " landmarks for " + countText(*true_landmarks) + " true ones (" +
		   countText(stats.number("landmarks_duplicated").value_or(0)) + " duplicated, " +
		   countText(stats.number("landmarks_spurious").value_or(0)) + " spurious)";
}

/// Given landmark IDs, a consistent filter's 0.9999 gate (chi-square 2 dof:
/// 18.4) rejects about one measurement in 10^4, plus the misread IDs it
/// should reject. It rejects a share q when the innovations it sees are k
/// times the covariance it predicts, q = exp(-18.4 / 2k): q = 1/4 needs
/// k = 6.6, innovations 2.6 times larger in sigma than predicted. Beyond a
/// quarter the gate throws valid re-observations away: the filter has lost
/// its consistency rather than being mildly over-confident.
std::optional<std::string> idsRejected(const Stats& stats)
{
	constexpr double kMaxIdRejectedShare = 0.25;
	const double given = stats.number("da_id_given").value_or(0);
	const double rejected = stats.number("da_id_rejected").value_or(0);
	if (given == 0 || rejected <= kMaxIdRejectedShare * given) return std::nullopt;
	return "it rejected " + countText(rejected) + " of the " + countText(given) +
		   " measurements whose landmark ID it was given (" + percentText(rejected, given) + ")";
}

/// Without IDs: more measurements rejected than used.
std::optional<std::string> mostlyRejected(const Stats& stats)
{
	const double rejected = stats.number("da_rejected").value_or(0);
	const double used = usedMeasurements(stats);
	if (rejected <= used) return std::nullopt;
	return "it rejected " + countText(rejected) + " of " + countText(rejected + used) + " measurements";
}

/// With ground truth: a map far more certain than it is right. The mean
/// landmark NEES (2 dof) of a consistent map is 2; a map whose covariances
/// are k times too small gives 2k. Above kMaxLandmarkNeesMean = 100 (k =
/// 50: errors 7 times the sd the map claims) the estimate is wrong rather
/// than over-confident: with IDs on MRCLAM dataset 6 the committed filters
/// reach 21.9 (SLSJF, robot 5), and the runs that pass 100 there are
/// associations gone wrong (1.8-7.2 m off where the barcodes give 0.2-0.8 m).
std::optional<std::string> inconsistentMap(const Stats& stats)
{
	constexpr double kMaxLandmarkNeesMean = 100;
	const auto nees = stats.number("landmark_nees_mean");
	if (!nees || *nees <= kMaxLandmarkNeesMean) return std::nullopt;
	std::ostringstream reason;
	reason << std::fixed << std::setprecision(1) << "its landmarks stand " << std::sqrt(*nees / 2)
		   << " times further from the ground truth than their covariance says (mean landmark NEES "
		   << std::setprecision(0) << *nees << ", 2 when consistent)";
	return reason.str();
}
}  // namespace

std::optional<std::string> suspectReason(const Stats& stats)
{
	for (const auto rule : {emptyResult, neverMatched, mapTooLarge, idsRejected, mostlyRejected, inconsistentMap})
		if (auto reason = rule(stats)) return reason;
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
