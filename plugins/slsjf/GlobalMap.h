#pragma once
/// \file GlobalMap.h
/// The SLSJF global map (book eq. 5.3): every feature and every local map's
/// end pose (and a start pose of its own for a map linked by odometry) as
/// variables of the sparse information core, and Algorithm 5.1's steps 1,
/// 3, 4 and 5 on it. The first map's start pose is the global origin, a
/// constant; with start(k+1) = end(k) the two are one variable, so the state
/// holds one pose per map (Table 5.1: 400 poses, dimension 2952).
///
/// It keeps every fused map's virtual observation (and every link), so the
/// whole problem can be relinearised at the current estimate: Gauss-Newton
/// on the local-map formulation, which the authors' I-SLSJF does.
///
/// Each fusion is linearised once (eq. 5.9), where the book takes the
/// current estimate; with first-estimates Jacobians (FEJ, Huang, Mourikis &
/// Roumeliotis 2010) every Jacobian is taken at each variable's first
/// estimate instead, the innovation still at the current one. Maps fused at
/// different estimates of the same variables then no longer inform
/// directions no map observes (the chain's rotation about the origin), the
/// over-confidence that turns the book's filter's map on real data (docs/plugins/slsjf.md
/// and docs/results/slsjf-jacobians.md have the figures). FEJ's points can be metres from the
/// estimate after a long loop closes; the observability-constrained
/// Jacobians (ObservabilityConstraint.h) keep the current point and only
/// the shared null space.

#include "VirtualObservation.h"

#include <esif/core/Estimate.h>
#include <esif/localmap/LandmarkIdAllocator.h>
#include <esif/localmap/LocalMap.h>
#include <esif/sparse/SparseInformationCore.h>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace esif::slsjf
{
/// What the overlap test of Sec. 5.4.1.1 needs of a fused map.
struct MapExtent
{
	double radius_m = 0;  ///< farthest reach of the map's features from its origin, with sigmas [m]
	double start_uncertainty_m = 0;	 ///< sigmas of the start position when the map was fused [m]
};

/// Where each fusion's Jacobians are taken (the file comment explains).
enum class FusionJacobians
{
	Current,		 ///< the current estimate (the book)
	FirstEstimates,	 ///< each variable's first estimate (FEJ)
	/// the current estimate, projected so that every fusion shares the
	/// rigid-motion null space of the first estimates (ObservabilityConstraint.h)
	ObservabilityConstrained
};

/// One fused local map as the global map keeps it.
struct FusedMap
{
	std::size_t index = 0;	///< k
	/// The rawlog step the map ended at; nullopt for a map read from files.
	std::optional<std::size_t> last_step;
	std::optional<VarId> start;	 ///< nullopt: the global origin
	VarId end;
	std::vector<VarId> features;  ///< the global variable of each kept local feature, in z's order
	VirtualObservation observation;
	MapExtent extent;
};

/// The odometry link of eq. (5.4)-(5.6) between two poses.
struct LinkTerm
{
	std::optional<VarId> from;	///< nullopt: the global origin
	VarId to;
	Pose2 u;
	Eigen::Matrix3d Q;
};

class GlobalMap
{
   public:
	/// `jacobians`: where each fusion is linearised (see above).
	GlobalMap(const SparseRecoveryParams& params, FusionJacobians jacobians);

	/// Step 1 of Algorithm 5.1: the start pose of `map`. Map 1 starts at the
	/// origin (nullopt); a later map at the previous end pose; a map with a
	/// link at a new pose f(X_ke, u) fused with the link's information
	/// (eq. 5.4-5.6; the innovation is zero at that initial value).
	std::optional<VarId> startPose(const LocalMap& map);

	/// Steps 3-5: new features and the end pose initialised from the start
	/// pose (eq. 5.7), the map fused as one virtual observation (eq. 5.8-5.9,
	/// information-form update with the map's own information matrix), the
	/// state recovered (eq. 5.14). `decisions` holds one association per
	/// local feature: Matched (global id), New (proposed id: kept unless
	/// taken, then the next free one, written back) or Rejected (left out).
	void fuse(const LocalMap& map, std::optional<VarId> start, StepReport& decisions, const MapExtent& extent);

	/// Relinearises every fused map and link at the current estimate and
	/// solves again (Gauss-Newton), until no estimate moves more than
	/// `tolerance` or `max_iterations` are done; returns the iterations. The
	/// relinearised estimates are then every variable's first estimate.
	int relinearise(int max_iterations, double tolerance);

	Pose2 pose(VarId v) const { return core_->estimate(v); }
	Eigen::Vector2d point(VarId v) const { return core_->estimate(v); }
	/// Start pose estimate of a map (origin for nullopt).
	Pose2 startEstimate(const std::optional<VarId>& start) const;
	std::optional<VarId> featureVar(LandmarkId id) const;
	LandmarkId featureId(VarId v) const { return id_of_var_.at(v.value); }
	/// Feature variables in order of creation.
	const std::vector<VarId>& featureVars() const { return feature_vars_; }
	const std::vector<FusedMap>& fusedMaps() const { return fused_; }
	std::size_t poseCount() const { return poses_; }

	/// Joint covariance of `vars` (covariance columns, eq. 3.25).
	Eigen::MatrixXd covariance(const std::vector<VarId>& vars) { return core_->covariance(vars); }
	/// Every variable's marginal covariance (sparse inverse), in VarId order.
	std::vector<Eigen::MatrixXd> marginals() { return core_->marginalCovariances(); }

	SparseInformationCore& core() { return *core_; }
	const SparseInformationCore& core() const { return *core_; }
	/// The state of eq. (5.3) with its information matrix: features by ID,
	/// each end pose by its map and step; a linked map's own start pose by
	/// neither (a reference never has it, so the test marginalises it).
	StateInformation stateInformation() const;
	/// Counters of the current core plus those of the cores relinearisation replaced.
	SparseCounters counters() const;

   private:
	/// Where a term's Jacobian is taken for variable v.
	using LinearisationPoint = std::function<Eigen::VectorXd(VarId)>;

	VarId addFeature(LandmarkId proposed, const Eigen::Vector2d& initial, LandmarkId& id);
	VarId newPose(const Pose2& initial);
	VarId newPoint(const Eigen::Vector2d& initial);
	/// Where a fusion's Jacobian is taken: the first estimate (FEJ) or the
	/// current one, as configured.
	LinearisationPoint fusionPoint() const;
	/// Where the shared null space is taken (observability-constrained
	/// Jacobians: the first estimates), or none.
	std::optional<LinearisationPoint> nullSpacePoint() const;
	/// A link term (eq. 5.4-5.6) and a map term (eq. 5.8-5.9); with
	/// `null_space_at`, a relative term's Jacobian is projected onto that
	/// point's rigid-motion null space.
	static void addLinkTerm(SparseInformationCore& core, const LinkTerm& link, const LinearisationPoint& at,
							const std::optional<LinearisationPoint>& null_space_at = std::nullopt);
	static void addMapTerm(SparseInformationCore& core, const FusedMap& map, const LinearisationPoint& at,
						   const std::optional<LinearisationPoint>& null_space_at = std::nullopt);
	std::unique_ptr<SparseInformationCore> rebuiltCore() const;
	/// After a relinearisation the relinearised estimates are the first ones.
	void restartFirstEstimates();

	SparseRecoveryParams params_;
	FusionJacobians jacobians_;
	std::unique_ptr<SparseInformationCore> core_;
	std::vector<Eigen::VectorXd> first_estimates_;	///< by VarId value
	std::vector<FusedMap> fused_;
	std::vector<LinkTerm> links_;
	std::map<LandmarkId, VarId> var_of_id_;
	std::map<int, LandmarkId> id_of_var_;
	std::vector<VarId> feature_vars_;
	std::size_t poses_ = 0;
	LandmarkIdAllocator ids_;
	SparseCounters retired_;  // counters of cores replaced by relinearisation
};

}  // namespace esif::slsjf
