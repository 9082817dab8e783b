#pragma once
/// \file LocalMapEvaluation.h
/// Accuracy of a run on local-map input against the ground truth stored
/// beside the maps (LocalMapFiles.h): ground_truth_landmarks.txt and
/// ground_truth_end_poses.txt are already in the global frame, the frame of
/// pose 0 that every joining filter estimates in, so nothing is transformed
/// or fitted. Landmarks are paired through `filter_to_true` (the audit's
/// majority vote, identity when the plugin kept the files' IDs), end poses
/// by map index k. The figures are those of esif::evaluate (Evaluator.h).

#include <esif/eval/Evaluator.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/LocalMapFiles.h>
#include <esif/formats/RunRecord.h>

#include <map>
#include <optional>
#include <vector>

namespace esif
{
/// The folder's ground truth as a GroundTruth for the map writers:
/// landmarks as given, `path` the true end poses in order of k. nullopt
/// when the folder has neither file.
std::optional<GroundTruth> localMapGroundTruth(const LocalMapFolder& folder);

/// Landmark RMSE, NEES and consistent fraction against the true landmarks,
/// end-pose ATE and pose NEES against the true end poses (`end_poses`:
/// step = k). nullopt when the folder has no ground truth; a figure whose
/// truth file is absent stays empty.
std::optional<Accuracy> evaluateLocalMapRun(
	const LocalMapFolder& folder, const std::vector<TrajectoryPoint>& end_poses, const Estimate& estimate,
	const std::map<LandmarkId, LandmarkId>& filter_to_true);

}  // namespace esif
