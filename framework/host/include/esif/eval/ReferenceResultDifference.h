#pragma once
/// \file ReferenceResultDifference.h
/// How far a run on local maps is from a reference joined result in the
/// layout of the authors' Linear SLAM output (`--reference-result DIR`:
/// feature.txt, pose.txt; LocalMapFiles.h), a near-optimal answer for the
/// same maps. Both are in the frame of pose 0, so no alignment is fitted.
/// Landmarks are paired by the files' feature IDs (the run's own IDs mapped
/// through `filter_to_file`), end poses by map index k; headings are
/// compared modulo 2 pi, since the reference's are not wrapped.

#include <esif/core/Estimate.h>
#include <esif/formats/LocalMapFiles.h>
#include <esif/formats/RunRecord.h>
#include <esif/formats/StatsJson.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// A statistic is nullopt when there is nothing to compare.
struct ReferenceResultDifference
{
	std::size_t landmarks_matched = 0;	///< estimated landmarks whose file ID the reference has, both finite
	std::optional<double> landmark_rms_m;
	std::optional<double> landmark_max_m;
	std::size_t poses_matched = 0;	///< end poses k the reference has, both finite
	std::optional<double> pose_rms_m;  ///< position difference of the end poses [m]
	std::optional<double> pose_max_m;
	std::optional<double> heading_rms_deg;	///< heading difference wrapped to (-180, 180] [deg]
};

/// `estimate` and `end_poses` (step = k) against `reference`.
/// `filter_to_file` maps each estimated landmark to a file feature ID;
/// landmarks without one are left out.
ReferenceResultDifference referenceResultDifference(
	const Estimate& estimate, const std::vector<TrajectoryPoint>& end_poses,
	const std::map<LandmarkId, LandmarkId>& filter_to_file, const ReferenceResult& reference);

/// The stats keys setReferenceResultStats writes, in table order:
/// refres_landmark_rms_m, refres_landmark_max_m, refres_landmarks_matched,
/// refres_pose_rms_m, refres_pose_max_m, refres_heading_rms_deg, refres_poses_matched.
const std::vector<std::string>& referenceResultKeys();

/// Adds the difference under referenceResultKeys() (null for a nullopt statistic).
void setReferenceResultStats(Stats& stats, const ReferenceResultDifference& difference);

}  // namespace esif
