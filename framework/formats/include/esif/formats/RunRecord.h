#pragma once
/// \file RunRecord.h
/// Everything one replay produced, as handed to the writers and evaluators.

#include <esif/core/Estimate.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/RawlogReader.h>

#include <mrpt/obs/CSensoryFrame.h>

#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// The filtered robot pose after one step.
struct TrajectoryPoint
{
	std::size_t step = 0;
	double time_s = 0;
	PoseEstimate pose;
};

/// A pose of the map with the sensory frame observed there.
struct Keyframe
{
	PoseEstimate pose;
	/// Null when the replay did not keep the log's frames: the map writer
	/// then reads it again from RunRecord::frames_source.
	mrpt::obs::CSensoryFrame::Ptr frame;
	/// The step the frame was taken at, so that a smoother's re-estimated
	/// trajectory (FilterPlugin::smoothedTrajectory) can replace `pose`.
	std::size_t step = 0;
};

struct RunRecord
{
	std::string plugin;	 ///< plugin class name
	std::string rawlog;	 ///< rawlog path
	std::vector<TrajectoryPoint> trajectory;
	std::vector<Keyframe> keyframes;
	/// The rawlog to read the keyframes' frames from when they were not kept
	/// (RawlogFrames.h); none when every keyframe holds its frame.
	std::optional<RawlogSource> frames_source;
	Estimate final_estimate;
	/// Ground truth in the initial-pose frame (the estimate's frame), if known.
	std::optional<GroundTruth> truth;
};

}  // namespace esif
