#pragma once
/// \file DslamLocalMapJoining.h
/// The D-SLAM Local Map Joining Filter (book Ch. 4): local EKF maps are
/// reduced to the relative geometry of their features (distances from a
/// reference feature f1 and angles from the baseline f1 -> f2, eq.
/// 4.9-4.12, the robot pose marginalised) and fused into a global map of
/// features only by D-SLAM's EIF (eq. 4.13-4.17), whose information matrix
/// is exactly sparse: only features of one local map are linked (eq.
/// 4.18-4.19). There is no robot in the state; its global pose comes from
/// two mapped features of the open local map (Sec. 4.4.1).
///
/// Per closed local map (the book has no algorithm box for Ch. 4; the order
/// of DSLAM-LMJ.md §10): the first map's features are the global map (an
/// anchor, the only absolute information); a later map is associated at the
/// upper level (Sec. 4.4.2), reduced to z_map with the pair (f1, f2) among
/// its mapped features, its new features placed by eq. 4.16, fused by eq.
/// 4.17, and the state recovered (incremental Cholesky, Sec. 4.4.3). A map
/// sharing fewer than two features with the global map (Sec. 4.4.4 fails:
/// map 132 of the authors' Victoria Park maps) is joined with the next map
/// through their shared pose first (mergeConsecutiveLocalMaps), as the
/// authors' later code does; the estimate lags by one map (Sec. 4.6.1).

#include "DslamLmjParams.h"
#include "GlobalFeatureMap.h"
#include "JoinedMaps.h"
#include "UpperLevelAssociation.h"

#include <esif/plugin/MapJoiningPlugin.h>
#include <esif/plugin/PluginWithParams.h>

#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace esif
{
/// The global map and its fusions are lmj::GlobalFeatureMap's; this class
/// decides what is fused when: which association, and what to do with a map
/// that cannot be fused alone.
class DslamLocalMapJoining : public PluginWithParams<lmj::DslamLmjParams, MapJoiningPlugin>
{
	DEFINE_MRPT_OBJECT(DslamLocalMapJoining, esif)

   public:
	DslamLocalMapJoining() : PluginWithParams("D-SLAM map joining") {}
	std::string sectionName() const override { return "dslam_lmj"; }
	PoseEstimate robotPose() const override;
	Estimate estimate() const override;
	CostFigures costFigures() const override;
	Formulation formulation() const override { return Formulation::DslamLocalMapJoining; }
	std::optional<StateInformation> stateInformation() const override;

	std::vector<PoseEstimate> endPoses() const override;
	StepReport mapReport(std::size_t k) const override;
	std::vector<LocalMapFusionCost> fusionCosts() const override { return costs_; }

   protected:
	/// The first map's features are the global map; a later map is
	/// associated, reduced to its relative geometry and fused (see above).
	void fuseLocalMap(const LocalMap& map) override;
	void finishJoining() override;
	/// The upper-level association needs IDs on every map after the first.
	void checkGivenMap(const LocalMap& map) const override;
	std::vector<SettledFusion> settledFusions() const override;
	SparseInformationCore& globalInformation() const override;
	/// With upper_level_frame = start_pose, the close rule's count of own
	/// features in the global map (Sec. 4.4.4 without IDs).
	std::optional<std::size_t> ownFeaturesInGlobalMap(
		const LandmarkEkf& open_map, const std::set<LandmarkId>& own_ids) const override;
	/// The supported global features within `radius_m` of the open map's
	/// start (openMapFrame), moved into its frame. The start pose and the
	/// features are taken as independent, as the start-pose frame of the
	/// upper-level association takes them (the start pose comes from a pair
	/// of them, Sec. 4.4.1, whose correlation with it is not kept).
	std::optional<EarlierFeatures> globalFeaturesNearOpenMapStart(double radius_m) override;

   private:
	void start() override;
	void requireConfigured() const;
	/// Fuses `maps` (association `decided` when already made); false, with
	/// nothing changed, when fewer than two of its features are usable in
	/// the global map, or when no reference pair of an association made here
	/// passes keepReferencePairInReach.
	bool tryFuse(const lmj::JoinedMaps& maps, double seconds_before, std::optional<lmj::UpperLevelOutcome> decided);
	bool joinWithLastFusion(const lmj::JoinedMaps& maps);
	/// Sec. 4.4.1 before a fusion: the end pose `map` gets through its
	/// reference pair (GlobalFeatureMap::endThroughPair) must agree with the
	/// end pose its start reaches (startOf composed with the map's own)
	/// within reference_pair_chi2_quantile (3 dof), the test robotPose()
	/// makes of the open map. A pair that fails has its two matches
	/// Rejected, and the next pair is tried; pairs of features matched to
	/// `excluded` are not chosen. A pair matched wrongly after a blind drive
	/// can pass the association's joint test under the start's wide
	/// uncertainty and still move the robot by metres
	/// (docs/plugins/dslam_lmj.md, "A fusion that moves the robot too far").
	enum class PairReach
	{
		NoPair,		///< no pair to test
		InReach,	///< a pair passed (the pairs before it left out)
		OutOfReach	///< every pair failed, and was left out
	};
	PairReach keepReferencePairInReach(const LocalMap& map, StepReport& decisions,
									   const std::vector<LandmarkId>& excluded = {});
	/// The joined map's association, made while the last fusion is still in;
	/// nullopt when it leaves no reference pair outside `created` within the
	/// joined map's start's reach.
	std::optional<lmj::UpperLevelOutcome> associateBeforeWithdrawing(
		const LocalMap& joined, const std::vector<LandmarkId>& created);
	bool useIds(const LocalMap& map) const;
	/// Keeps in a joined map's update the features the withdrawn fusion created.
	void keepFeaturesOfWithdrawnFusion(const LocalMap& joined, const std::vector<LandmarkId>& created,
									   lmj::UpperLevelOutcome& decided) const;
	std::optional<lmj::UpperLevelOutcome> associate(const LocalMap& map, const Eigen::MatrixXd& feature_cov);
	void giveUpPendingMap();
	PoseEstimate openMapFrame() const;
	/// Where `map` starts in the global frame: the end pose of the map
	/// before it (the global origin for map 1), then its link if it has one.
	PoseEstimate startOf(const LocalMap& map) const;
	std::optional<LandmarkId> globalIdOfOpenFeature(LandmarkId id) const;

	// Behind const robotPose()/estimate(): recovery caches.
	std::unique_ptr<lmj::GlobalFeatureMap> global_;
	std::map<std::size_t, std::vector<LandmarkId>> feature_ids_of_map_;	 // original map k -> its feature IDs
	// A map that could not be fused, nor joined with the last fusion, waits for the next.
	std::optional<lmj::JoinedMaps> pending_;
	std::vector<LocalMapFusionCost> costs_;	 // one per fusion in the global map, in order

	struct Tally
	{
		MapAssociationTally association;
		std::size_t maps_merged = 0, maps_unjoinable = 0;
		/// Joins (joinConsecutive) that left a feature the two maps place
		/// apart out of the later map, and joins with the last fusion refused
		/// for such a feature.
		std::size_t join_features_left_out = 0, joins_refused = 0;
		/// Fusion attempts refused because no reference pair placed the map's
		/// end pose within its start's reach, and pairs whose matches were
		/// rejected for it (keepReferencePairInReach). A map refused is
		/// joined with the last fusion or with the next map, and may be
		/// attempted again.
		std::size_t fusions_refused = 0, reference_pairs_refused = 0;
	} tally_;
};

}  // namespace esif
