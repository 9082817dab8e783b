#pragma once
/// \file DslamLmjParams.h
/// Parameters of the D-SLAM local map joining plugin, INI section
/// [dslam_lmj]: the upper-level data association (Sec. 4.4.2), the
/// reference pair of each local map (Sec. 4.2.2), the local-map builder
/// (with the two-common-features rule of Sec. 4.4.4) and the sparse recovery.

#include <esif/relative/FeatureMap.h>
#include <esif/config/ParamBinder.h>
#include <esif/localmap/LocalMapBuilderParams.h>
#include <esif/localmap/MapLevelAssociationParams.h>
#include <esif/sparse/SparseRecoveryParams.h>

namespace esif::lmj
{
/// Where a closed local map's features meet the global map's candidates
/// when its features carry no IDs (Sec. 4.4.2).
enum class UpperLevelFrame
{
	/// In the frame of two local features already known to be global ones
	/// (matched to the previous map by the local level): the book.
	Pair,
	/// In the map's own frame, placed by its start pose: the end pose of the
	/// map before it, located through that map's pair (Sec. 4.4.1), as
	/// SLSJF places a local map (Sec. 5.4.1). Needs no feature known in
	/// advance, so a map whose trees were seen by an earlier map but not by
	/// the previous one can still be associated.
	StartPose
};

/// The upper-level association (MapLevelAssociationParams: with jcbb or nn,
/// in the frame of two common features known from the local level, Sec.
/// 4.4.2; with IDs the gate is tested in a reference pair's frame) and the rest.
struct DslamLmjParams : MapLevelAssociationParams
{
	/// Region pruning (Sec. 4.4.2): candidates lie within the local map's
	/// reach from f1 plus Delta = region_sigmas * sigma_max(f1 global) + this [m].
	double region_margin_m = 2.0;
	double region_sigmas = 3.0;	 ///< the k_sigma of Delta (the authors' SigmaMultiplier)
	/// Without IDs: pair (the book) or start_pose (see UpperLevelFrame).
	UpperLevelFrame upper_level_frame = UpperLevelFrame::Pair;
	/// Reference pair (Sec. 4.2.2, eq. 4.7): the widest baseline among mapped
	/// features at least this far apart [m] ...
	double reference_min_separation_m = 1.0;
	/// ... whose members have no other feature of the map this close [m]:
	/// an angle alpha_i12 is undefined when d_1i -> 0.
	double reference_min_clearance_m = 0.2;
	/// Between fusions, a pair of the open map places the robot (Sec. 4.4.1)
	/// only if that pose and the open map's start composed with the robot's
	/// pose in it agree within this chi-square quantile (3 dof); a misread
	/// feature carries a neighbour's ID and fails it. The same test holds a
	/// closed map's end pose, placed through the pair its fusion would use,
	/// against its start composed with its end pose in it: a failing pair's
	/// matches are left out, and a map with no pair that passes is not fused
	/// (DslamLocalMapJoining::keepReferencePairInReach). 1 = every pair is
	/// trusted (the book).
	double reference_pair_chi2_quantile = 0.9999;
	/// After each fusion, Gauss-Newton passes over the global map: every
	/// earlier update (eq. 4.17) evaluated again at the current estimate
	/// (FeatureMap::relinearise), until none moved. false: never (the book's
	/// EIF linearises each map once, at the estimate before its fusion).
	bool relinearise_after_fusion = false;
	/// ... at most this many passes (as [dslam] relinearise_iterations: the
	/// passes of one relinearisation).
	int relinearise_iterations = 5;
	/// Where each fusion (eq. 4.17) is linearised: at the estimate of its
	/// time (the book) or at one point per feature shared by every fusion and
	/// moved only by relinearisation (FeatureMap::shareLinearisationPoints:
	/// the first-estimates Jacobians of a relative map).
	relative::MapLinearisation map_linearisation = relative::MapLinearisation::Current;
	/// Only updates whose features' relative geometry moved more than this
	/// since their last linearisation are evaluated again [m].
	double relinearise_threshold_m = 0.01;

	LocalMapBuilderParams builder = defaultBuilder();  ///< local maps built from a rawlog
	SparseRecoveryParams recovery = defaultRecovery();	///< recovery, reordering, n0 (Sec. 4.4.3, 3.3)

	void declare(ParamBinder& b);
	/// The builder closes a map only once it holds two features of the
	/// previous map (Sec. 4.4.4).
	static LocalMapBuilderParams defaultBuilder();
	static SparseRecoveryParams defaultRecovery();
};

}  // namespace esif::lmj
