#pragma once
/// \file GlobalFeatureMap.h
/// The global map of D-SLAM map joining (book Ch. 4): features only (eq.
/// 4.1), estimated by D-SLAM's EIF on the SDK's relative::FeatureMap, and
/// the record of every fusion that built it. The first fusion is the anchor
/// (Sec. 4.3: a map's features, robot marginalised, the only absolute
/// information the global map ever gets); each later one is a local map's
/// relative geometry about a reference pair (f1, f2) of features already
/// mapped (eq. 4.9-4.17), its new features given fresh IDs. After each
/// fusion the state is recovered (Sec. 4.4.3) and, with
/// relinearise_after_fusion, relinearised; the end poses of the original
/// maps in it are then located through the pair (Sec. 4.4.1).
///
/// The last fusion can be withdrawn, so that the plugin can join it with a
/// map that cannot be fused alone (Sec. 4.4.4) and fuse the two anew.

#include "DslamLmjParams.h"
#include "JoinedMaps.h"

#include <esif/core/Estimate.h>
#include <esif/localmap/LandmarkIdAllocator.h>
#include <esif/relative/FeatureMap.h>

#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace esif::lmj
{
/// The end pose of one original local map, as needed for Sec. 4.4.1.
struct EndPose
{
	std::size_t map = 0;  ///< k
	Pose2 local = Pose2::Zero();  ///< in the frame of the fused map it belongs to
	Eigen::MatrixXd local_cov;	///< joint covariance of (end pose, f1, f2) in that frame (7 x 7)
	PoseEstimate global;
};

/// One fusion: one local map, or several joined through their shared poses.
struct Fusion
{
	JoinedMaps source;	///< what was fused (kept to join it with a later map if needed)
	std::vector<LandmarkId> local_ids;	///< its feature IDs, in order
	StepReport decisions;  ///< one per feature: global id or rejected
	relative::MapUpdate update;	 ///< to withdraw it
	bool anchor = false;  ///< the first map: the global map's only absolute information
	Eigen::Vector2d f1_local = Eigen::Vector2d::Zero(), f2_local = Eigen::Vector2d::Zero();
	LandmarkId f1 = -1, f2 = -1;  ///< the pair that locates the end poses (-1: not fused)
	std::vector<EndPose> ends;
	std::size_t rejected = 0;
};

class GlobalFeatureMap
{
   public:
	/// Reads the recovery, map_linearisation, relinearisation and
	/// reference-pair keys of `params`.
	explicit GlobalFeatureMap(const DslamLmjParams& params);

	/// The anchor is in (no later fusion can be made before it).
	bool anchored() const { return anchored_; }
	/// Fuses `maps` as the anchor (Sec. 4.3); false, with nothing changed,
	/// when its features hold no reference pair.
	bool fuseAnchor(const JoinedMaps& maps);
	/// Fuses `maps` by eq. 4.10-4.17 with `decisions` (one per feature:
	/// Matched global id, New proposed id or Rejected); false, with nothing
	/// changed, when no two of its features mapped in the global map make a
	/// reference pair.
	bool fuseRelative(const JoinedMaps& maps, const StepReport& decisions);
	/// The reference pair fuseRelative(maps, decisions) updates about (eq.
	/// 4.9): two of the map's features matched to supported global features,
	/// none of them matched to one of `excluded`; nullopt when none can be
	/// chosen.
	std::optional<std::pair<int, int>> referencePairOf(
		const LocalMap& map, const StepReport& decisions, const std::vector<LandmarkId>& excluded = {}) const;
	/// The map's end pose placed through `pair` of its features and their
	/// global features (Sec. 4.4.1), at the global estimate before the map's
	/// update: where its fusion would put it. `map_cov`: the map's
	/// covariance (LocalMap::covarianceMatrix()).
	PoseEstimate endThroughPair(const LocalMap& map, const Eigen::MatrixXd& map_cov, const StepReport& decisions,
								std::pair<int, int> pair);
	/// The features no fusion but the last informs: those the last fusion
	/// created, and those it carried for a fusion withdrawn before it.
	/// Withdrawing it leaves them without information until fused again.
	std::vector<LandmarkId> informedOnlyByLast() const;
	/// Takes back the last fusion (its features stay, without its
	/// information, until fused again) and returns its record.
	Fusion withdrawLast();
	/// Records `maps` as unjoinable: not fused, every feature rejected, end
	/// poses carried from the last end pose.
	void addUnjoinable(const JoinedMaps& maps);
	/// Locates every fusion's end poses at the current estimate.
	void locateAllEnds();

	/// The global feature map itself (recovery caches behind it).
	relative::FeatureMap& features() { return map_; }
	const relative::FeatureMap& features() const { return map_; }
	const std::vector<Fusion>& fusions() const { return fusions_; }
	/// The fusion original map k is in; nullptr when none is yet.
	const Fusion* fusionOf(std::size_t k) const;
	/// A fused feature's local ID -> its global ID.
	const std::map<LandmarkId, LandmarkId>& globalOfLocal() const { return global_of_local_; }
	/// Global covariance of a feature pair (cached until the next fusion).
	Eigen::Matrix4d pairCovariance(LandmarkId f1, LandmarkId f2);
	/// The last end pose recorded (the global frame's origin before any).
	PoseEstimate lastEndPose() const;
	/// The end pose of original map k, once a fusion (or an unjoinable
	/// record) holds it.
	std::optional<PoseEstimate> endPoseOf(std::size_t k) const;
	/// Every original map's end pose, by map index.
	std::vector<PoseEstimate> endPoses() const;
	/// Original maps fused (unjoinable ones not counted).
	std::size_t mapsFused() const;
	std::size_t relinearisedTerms() const { return relinearised_terms_; }
	/// Relinearisation passes taken back because they raised the map's cost.
	std::size_t rejectedRelinearisations() const { return map_.rejectedPasses(); }

   private:
	/// A fusion's record before its update: what was fused and its IDs.
	static Fusion openRecord(const JoinedMaps& maps);
	/// Recovery, relinearisation and records of a fusion whose update is
	/// made; `order` lists its kept features as updated, the pair first.
	void settle(Fusion fusion, const std::vector<int>& order, const Eigen::MatrixXd& P);
	void relinearise(const Eigen::Vector2d& reference);
	static void recordEnds(Fusion& fusion, const Eigen::MatrixXd& pair_cov);
	void locateEnds(Fusion& fusion);
	/// A new feature's global ID: `proposed` unless the global map or this
	/// fusion (`taken_now`, appended to) already has it.
	LandmarkId freshId(LandmarkId proposed, std::vector<LandmarkId>& taken_now);
	std::optional<std::pair<int, int>> referencePair(
		const std::vector<Eigen::Vector2d>& points, const std::vector<int>& eligible) const;

	relative::FeatureMap map_;
	double reference_min_separation_m_, reference_min_clearance_m_;
	bool relinearise_after_fusion_;
	double relinearise_threshold_m_;
	int relinearise_iterations_;

	std::vector<Fusion> fusions_;
	std::map<std::size_t, std::size_t> fusion_of_map_;	// original map k -> fusions_ index
	std::map<LandmarkId, LandmarkId> global_of_local_;	// a fused feature's local ID -> global ID
	bool anchored_ = false;	 // the first map is in
	LandmarkIdAllocator ids_;
	std::map<std::pair<LandmarkId, LandmarkId>, Eigen::Matrix4d> pair_cov_cache_;  // cleared by every fusion
	std::size_t relinearised_terms_ = 0;
};

}  // namespace esif::lmj
