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

/// How a run folder is read back: as a run being compared, whose rows may
/// be NaN where it diverged, or as the reference others are measured
/// against, held to the bounds of every reference input (InputBounds.h):
/// positions finite and within kMaxCoordinate_m, headings finite, landmark
/// IDs in [0, kMaxLandmarkId].
enum class RunRole
{
	Compared,
	Reference
};

/// Reads a TUM trajectory. Each data line holds 8 numbers; the timestamp must
/// be finite and strictly increasing; the yaw is taken from the quaternion
/// (qx, qy, qz, qw), which must not be zero. Throws InputError naming the file
/// (missing, unreadable) or "file:line" (malformed row, or out of bounds for
/// a reference).
std::vector<TimedPose2D> readTrajectoryTum(const std::string& path, RunRole role = RunRole::Compared);

/// Reads landmarks.txt: an integer ID and 5 numbers per data line, IDs
/// distinct. Throws InputError naming the file or "file:line".
std::vector<LandmarkEstimate> readLandmarksTxt(const std::string& path, RunRole role = RunRole::Compared);

/// Reads DIR/trajectory.tum, DIR/landmarks.txt and, when present,
/// DIR/landmark_identities.txt (which must list exactly the landmarks of
/// landmarks.txt, InputError naming it otherwise) of a run being compared.
RunOutputs readRunOutputs(const std::string& dir);

/// Reads them as the reference of other runs (compare --reference DIR, run
/// and localmaps check --reference-run DIR, export g2o --associations-from
/// DIR): RunRole::Reference, and, when `steps` is given, one trajectory row
/// per step of the rawlog (InputError naming the file otherwise). A diverged
/// run may be compared, never measured against.
RunOutputs readReferenceRun(const std::string& dir, std::optional<std::size_t> steps = std::nullopt);

/// A run's estimate as a reference in ground-truth form: its landmarks by
/// ID, its trajectory rows in order as the path.
GroundTruth runAsGroundTruth(const RunOutputs& run);

}  // namespace esif
