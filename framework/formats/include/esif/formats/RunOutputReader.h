#pragma once
/// \file RunOutputReader.h
/// Reads back the text outputs of `esif run` (see MapWriter.h):
/// trajectory.tum (`timestamp x y z qx qy qz qw`) and landmarks.txt
/// (`id x y cxx cxy cyy`), so that runs can be compared with each other
/// without ground truth. '#' lines and blank lines are skipped. `nan` and
/// `inf` are accepted where the writers may put them (a diverged landmark or
/// pose); a malformed or duplicated row throws InputError naming the file and
/// line.

#include <esif/core/Estimate.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/LandmarkIdentityFile.h>

#include <mrpt/math/TPose2D.h>

#include <optional>

#include <string>
#include <vector>

namespace esif
{
/// One row of trajectory.tum: the planar pose after one step.
struct TimedPose2D
{
	double time_s = 0;	///< the step's timestamp [s] (or the step index when the rawlog has no usable times)
	mrpt::math::TPose2D pose;  ///< x [m], y [m], phi [rad] in (-pi, pi], the yaw of the quaternion
};

/// The text outputs of one run folder.
struct RunOutputs
{
	std::vector<TimedPose2D> trajectory;  ///< in file order: strictly increasing times
	std::vector<LandmarkEstimate> landmarks;  ///< in file order: distinct IDs
	/// landmark_identities.txt, one row per landmark; none in a folder
	/// without it (another solver's solution read by `esif import g2o`).
	std::optional<LandmarkIdentities> identities;
};

/// Reads a TUM trajectory. Each data line holds 8 numbers; the timestamp must
/// be finite and strictly increasing; the yaw is taken from the quaternion
/// (qx, qy, qz, qw), which must not be zero. Throws InputError naming the file
/// (missing, unreadable) or "file:line" (malformed row).
std::vector<TimedPose2D> readTrajectoryTum(const std::string& path);

/// Reads landmarks.txt: an integer ID and 5 numbers per data line, IDs
/// distinct. Throws InputError naming the file or "file:line".
std::vector<LandmarkEstimate> readLandmarksTxt(const std::string& path);

/// Reads DIR/trajectory.tum, DIR/landmarks.txt and, when present,
/// DIR/landmark_identities.txt, which must list exactly the landmarks of
/// landmarks.txt (InputError naming it otherwise).
RunOutputs readRunOutputs(const std::string& dir);

/// A run's estimate as a reference in ground-truth form: its landmarks by
/// ID, its trajectory rows in order as the path.
GroundTruth runAsGroundTruth(const RunOutputs& run);

}  // namespace esif
