#pragma once
/// \file GroundTruth.h
/// Ground truth in the text formats MRPT's simul-landmarks writes:
/// `NAME_ground_truth.txt` (CLandmarksMap::saveToTextFile: x y z type
/// seenCount tLastSeen ID) and `NAME_ground_truth_robot_path.txt` ('%'
/// comment lines, then one row per step: x y z yaw pitch roll).

#include <esif/core/StepInput.h>
#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
struct GroundTruth
{
	std::map<LandmarkId, Eigen::Vector2d> landmarks;
	std::vector<Pose2> path;  ///< one pose per rawlog step; may be empty

	/// The same ground truth expressed in the frame of its first robot pose,
	/// the frame every filter estimates in (relative SLAM, Sec. 1.3.1).
	GroundTruth inInitialPoseFrame() const;
};

/// "DIR/NAME.rawlog" -> "DIR/NAME" (also strips ".rawlog.gz").
std::string groundTruthPrefixFor(const std::string& rawlog_path);

/// Loads PREFIX_ground_truth.txt and PREFIX_ground_truth_robot_path.txt.
/// Returns nullopt when the landmark file does not exist; a file that exists
/// but is malformed throws InputError with its name and line.
std::optional<GroundTruth> loadGroundTruth(const std::string& prefix);

/// Writes both files atomically in the same formats.
void saveGroundTruth(const GroundTruth& truth, const std::string& prefix);

}  // namespace esif
