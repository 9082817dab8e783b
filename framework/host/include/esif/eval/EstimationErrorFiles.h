#pragma once
/// \file EstimationErrorFiles.h
/// A run's errors against ground truth as two CSV files of its run folder,
/// written when ground truth is known, so that a Monte Carlo campaign can
/// average them over runs (`esif montecarlo`):
///   pose_errors.csv      step,ex_m,ey_m,eth_rad,nees,nees_position,nees_heading
///                        (one row per step)
///   landmark_errors.csv  true_id,ex_m,ey_m,nees        (final map)
/// An empty NEES field means none (initial pose, covariance not positive
/// definite). Numbers are written in their shortest exact form (round trip).
/// Pose files of earlier versions (step,ex_m,ey_m,eth_rad,nees) are still
/// read, without the split NEES, so older campaign folders stay usable.

#include <esif/eval/EstimationErrors.h>

#include <string>
#include <vector>

namespace esif
{
inline constexpr const char* kPoseErrorsFile = "pose_errors.csv";
inline constexpr const char* kLandmarkErrorsFile = "landmark_errors.csv";

std::string poseErrorsCsv(const std::vector<PoseError>& rows);
std::string landmarkErrorsCsv(const std::vector<LandmarkError>& rows);

/// Both files into `dir`, atomically and checked (AtomicFile.h).
void writeEstimationErrorFiles(
	const std::string& dir, const std::vector<PoseError>& poses, const std::vector<LandmarkError>& landmarks);

/// Read back; throw InputError naming the file and line for a missing file
/// or a malformed row.
std::vector<PoseError> readPoseErrors(const std::string& path);
std::vector<LandmarkError> readLandmarkErrors(const std::string& path);

}  // namespace esif
