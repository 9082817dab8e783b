#pragma once
/// \file LocalMapFiles.h
/// The local-map text format of the book's authors (Linear SLAM, 2D
/// I-SLSJF), so joining filters can run on their published maps and the
/// maps built here can be used by their tools. One folder holds
/// localmap_1.txt ... localmap_K.txt (no gap), each:
///
///     Ref            integer: the pose the map is expressed in (k-1; 0 = global origin)
///     N              integer: state dimension (3 + 2 n)
///     N lines        "id value": the end pose first (3 lines, id = -k: x, y, phi),
///                    then each feature (2 lines with the same positive id: x, y)
///     N lines        N numbers each: the information matrix, row-major
///
/// Optional files beside them:
///   ground_truth_landmarks.txt   `id x y` per true landmark, frame of pose 0
///   ground_truth_end_poses.txt   `k x y phi` per map end pose, frame of pose 0
///   links.txt                    `k dx dy dphi c11 c12 c13 c22 c23 c33`: map k's
///                                start pose is pose k-1 composed with this noisy
///                                odometry (eq. 5.4) instead of pose k-1 itself
///                                (an esif extension; the authors' maps have none)
///
/// Reading is strict, like the INI reader: a missing file in the sequence, a
/// wrong count, a non-number, a wrong id, a matrix not symmetric beyond
/// round-off or not positive definite throw InputError naming `file:line`
/// (the asymmetry of the authors' files, round-off of their MATLAB, is
/// removed by averaging the two triangles). Writing is atomic: a folder is
/// written under a temporary name beside DIR and renamed into place.

#include <esif/localmap/LocalMap.h>
#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// A folder of local maps with the ground truth found beside them.
struct LocalMapFolder
{
	std::vector<LocalMap> maps;	 ///< k = 1 ... K, in order
	/// ground_truth_landmarks.txt, in the frame of pose 0, if present.
	std::optional<std::map<LandmarkId, Eigen::Vector2d>> truth_landmarks;
	/// ground_truth_end_poses.txt: true end pose of map k, if present.
	std::optional<std::map<std::size_t, Pose2>> truth_end_poses;
};

/// Reads localmap_k.txt; `k` is the index the file name says. Sets each
/// feature's in_earlier_maps only from the file itself (false): the folder
/// reader sets it from the earlier maps' IDs. Ref must be k-1 (LocalMap has
/// no other start pose) and feature IDs positive; the information matrix is
/// returned symmetrised, `covariance` empty, phi wrapped.
LocalMap readLocalMapFile(const std::string& path, std::size_t k);

/// Reads DIR/localmap_1.txt ... up to the last one present (an index with no
/// file before the last is an error naming the missing file), links.txt and
/// the ground-truth files if present. A feature is in_earlier_maps when an
/// earlier map holds its ID. Throws InputError naming the folder when it
/// does not exist or holds no localmap_1.txt.
LocalMapFolder readLocalMapFolder(const std::string& dir);

/// Writes one map in the format above, full double precision (%.17g), atomically.
/// A map that would not read back (fails LocalMap::validate, a feature ID
/// <= 0, which the format keeps for poses) throws InputError and is not written.
void writeLocalMapFile(const LocalMap& map, const std::string& path);

/// Writes every map (and links.txt when a map has a link, the ground truth
/// when present) into the existing folder `dir` (an output folder's
/// partial folder: writeLocalMapFolder in LocalMapBuild.h writes a whole
/// folder). maps[i] must have index i+1. Throws InputError naming the file
/// that could not be written.
void writeLocalMapFiles(const LocalMapFolder& folder, const std::string& dir);

/// A joined result in the layout of the authors' Linear SLAM output:
/// DIR/feature.txt (`id x y`) and DIR/pose.txt (`k x y phi`, phi possibly
/// unwrapped), both in the frame of pose 0.
struct ReferenceResult
{
	std::map<LandmarkId, Eigen::Vector2d> features;
	std::map<std::size_t, Pose2> end_poses;
};

/// Reads DIR/feature.txt and DIR/pose.txt (both required: a reference
/// without its poses would leave refres_pose_* null unnoticed) for a folder
/// of `maps` local maps: feature IDs are MRPT's (1 to 2^31 - 1), a pose row
/// names one of the maps 1..`maps`; strict, InputError naming file:line.
ReferenceResult readReferenceResult(const std::string& dir, std::size_t maps);

}  // namespace esif
