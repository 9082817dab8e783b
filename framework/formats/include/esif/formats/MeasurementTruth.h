#pragma once
/// \file MeasurementTruth.h
/// The true landmark of every measurement of a simulated rawlog whose IDs
/// are not all true (Scenario::wrong_id_rate, spurious_rate):
/// PREFIX_ground_truth_measurement_ids.txt, beside the other ground-truth
/// files. One row per measurement in rawlog order:
///     step measurement rawlog_id true_id
/// (0-based step and measurement index; true_id -1: a spurious return,
/// which stands for no landmark). '%' lines are comments. Its per-step lists
/// have the shape and meaning of Rawlog::true_ids, so an evaluation can score
/// data association against them instead of the rawlog's own IDs.

#include <esif/core/StepInput.h>

#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// One measurement's ID as written to the rawlog and its true landmark.
struct MeasurementIds
{
	LandmarkId rawlog_id = 0;
	std::optional<LandmarkId> true_id;	///< none for a spurious return
};

/// Per step, per measurement (rawlog order).
using MeasurementTruth = std::vector<std::vector<MeasurementIds>>;

/// PREFIX + "_ground_truth_measurement_ids.txt".
std::string measurementTruthFileOf(const std::string& prefix);

/// Writes the file atomically.
void saveMeasurementTruth(const MeasurementTruth& truth, const std::string& prefix);

/// The file's true IDs in the shape of Rawlog::true_ids for a rawlog of
/// `steps` steps (steps without a row up to the last listed step are
/// empty); nullopt when the file does not exist (the rawlog's IDs are then
/// the truth). Throws InputError naming the file and line for a malformed
/// row, rows out of order or a step beyond `steps` (checked before
/// anything is allocated for it).
std::optional<std::vector<std::vector<std::optional<LandmarkId>>>> loadMeasurementTruth(
	const std::string& prefix, std::size_t steps);

}  // namespace esif
