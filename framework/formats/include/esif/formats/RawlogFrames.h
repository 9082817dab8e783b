#pragma once
/// \file RawlogFrames.h
/// The MRPT sensory frames of chosen steps, read again from the file a
/// Rawlog came from when it did not keep them (RawlogReadOptions::
/// keep_frames): one forward pass that holds one entry at a time, so a map
/// of keyframes is written without the whole log's frames in memory.
///
/// Only the file that was read is read again: its identity (RawlogSource) is
/// compared before the pass, since MRPT's deserialisers trust what they read
/// and only the first read was checked in a sandbox (RawlogReader.h), and
/// the checksum of its steps after it.

#include <esif/formats/RawlogReader.h>

#include <mrpt/obs/CSensoryFrame.h>

#include <functional>
#include <vector>

namespace esif
{
using FrameVisitor = std::function<void(std::size_t step, const mrpt::obs::CSensoryFrame::Ptr& frame)>;

/// Calls `each` with the frame of every step of `steps` (strictly
/// increasing), in order. Throws InputError naming the file when it changed
/// since it was read (identity or steps), or when a step of `steps` has no
/// frame (an odometry-only step) or lies beyond the log.
void readFramesAgain(const RawlogSource& source, const std::vector<std::size_t>& steps, const FrameVisitor& each);

}  // namespace esif
