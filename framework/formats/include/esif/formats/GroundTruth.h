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

/// Why `truth` cannot score a run of `steps` steps, or nullopt when it can.
/// Errors are measured in the frame of the initial robot pose, so without a
/// robot path the landmarks are in an unknown frame; a path must have one
/// pose per step, or one fewer (MRPT's simul-landmarks, e.g.
/// kf-slam_demo.rawlog, records no pose for the last step, which is then
/// left unscored), or more when the rawlog was cut short (`log_truncated`:
/// its steps are a prefix of the path's); any other length pairs poses with
/// the wrong steps.
std::optional<std::string> groundTruthProblem(const GroundTruth& truth, std::size_t steps, bool log_truncated);

/// "DIR/NAME.rawlog" -> "DIR/NAME" (also strips ".rawlog.gz").
std::string groundTruthPrefixFor(const std::string& rawlog_path);

/// PREFIX_ground_truth.txt and PREFIX_ground_truth_robot_path.txt.
std::vector<std::string> groundTruthFilesOf(const std::string& prefix);

/// Loads PREFIX_ground_truth.txt and PREFIX_ground_truth_robot_path.txt.
/// Returns nullopt when the landmark file does not exist; a file that exists
/// but is malformed throws InputError with its name and line.
std::optional<GroundTruth> loadGroundTruth(const std::string& prefix);

/// Writes both files atomically in the same formats.
void saveGroundTruth(const GroundTruth& truth, const std::string& prefix);

}  // namespace esif
