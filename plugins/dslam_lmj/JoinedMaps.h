#pragma once
/// \file JoinedMaps.h
/// What is offered to the global map in one fusion: one closed local map,
/// or several consecutive ones joined through their shared poses
/// (mergeConsecutiveLocalMaps). A map sharing fewer than two features with
/// the global map cannot be fused alone (Sec. 4.4.4 fails: map 132 of the
/// authors' Victoria Park maps); joined with its neighbour, as the authors'
/// later code does, it can. The joined map is in the frame of the first; the
/// end poses of the maps it absorbed are kept beside it, since each original
/// map's end pose must still be located in the global map (Sec. 4.4.1).

#include <esif/core/Estimate.h>
#include <esif/localmap/LocalMap.h>
#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace esif::lmj
{
/// End poses of the maps a joined map absorbed, in its frame, each with
/// its own 3x3 covariance.
using AbsorbedEnds = std::vector<std::pair<Pose2, Eigen::Matrix3d>>;

struct JoinedMaps
{
	LocalMap map;  ///< in the frame of the first original map, numbered as it
	std::vector<std::size_t> originals;	 ///< original indices k, in order
	AbsorbedEnds absorbed;	///< end poses of all originals but the last (that is map.end_pose)
};

/// One closed local map on its own.
JoinedMaps single(const LocalMap& map);

/// `earlier` and `later` (consecutive: later's first map starts where
/// earlier's last ends) as one map in the frame of `earlier`. A feature ID
/// both hold is one feature estimated from both (mergeConsecutiveLocalMaps),
/// except the features `left_out_of_later`, which are marginalised out of
/// `later` first, their sightings reported rejected.
JoinedMaps joinConsecutive(const JoinedMaps& earlier, const JoinedMaps& later,
						   const std::vector<LandmarkId>& left_out_of_later = {});

/// The feature IDs `earlier` and `later` both hold at two different points:
/// later's estimate, moved into earlier's frame through earlier's end pose,
/// outside the chi-square gate `gate_d2` (2 dof) of earlier's, under
/// earlier's joint covariance of [end pose; feature] and later's of the
/// feature (the maps are independent). Joined as one, such a feature turns
/// the two maps against each other: without landmark IDs the IDs come from
/// the scans' association with the global map, which after a blind turn can
/// give a cluster the ID of its neighbour 2 m away (MRCLAM robot 3, maps 5
/// and 6; docs/plugins/dslam_lmj.md, "Fewer than two common features").
std::vector<LandmarkId> disagreeingFeatures(const LocalMap& earlier, const LocalMap& later, double gate_d2);

}  // namespace esif::lmj
