#pragma once
/// \file FeatureMap.h
/// The feature-only map EIF of D-SLAM (book Ch. 3, Sec. 3.1.3) and of the
/// D-SLAM map-joining filter (Ch. 4): the state is the feature positions
/// only (eq. 3.10), estimated by an EIF on the sparse information core with
/// no prediction step. Two kinds of update:
/// - relative: z_map of a scan (or of a virtual observation; in Ch. 4, of a
///   local map), eq. (3.12) and (3.15); new features are first placed by
///   eq. (3.14);
/// - anchor: while no scan has yet been admissible, the features seen from
///   the initial pose (the map frame, known exactly) get a joint prior.
/// The last update can be withdrawn (Sec. 3.4.1).

#include <esif/config/ParamBinder.h>
#include <esif/core/Estimate.h>
#include <esif/relative/RelativeGeometry.h>
#include <esif/sparse/SparseInformationCore.h>

#include <Eigen/Cholesky>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace esif::relative
{
/// An applied map update, kept so it can be withdrawn.
struct MapUpdate
{
	UpdateTerm term;
	std::vector<LandmarkId> new_features;  ///< features this update created
	long kept_index = -1;				   ///< its entry among the kept terms, if kept
};

/// Where a feature map's relative updates are linearised.
enum class MapLinearisation
{
	/// One point per feature, shared by all updates and moved only by
	/// relinearisation (FeatureMap::shareLinearisationPoints explains why).
	Shared,
	/// The estimate at each update's time, as the book's EIF.
	Current
};

/// Declares key `map_linearisation` (shared | current) for `field`.
void declareMapLinearisation(ParamBinder& b, MapLinearisation& field);

class FeatureMap
{
   public:
	explicit FeatureMap(const SparseRecoveryParams& params);

	bool contains(LandmarkId id) const { return var_of_.count(id) > 0; }
	/// Mapped and informed by an update still in force (not only by a
	/// withdrawn one): usable as a reference feature.
	bool supported(LandmarkId id) const { return contains(id) && !unsupported_.count(id); }
	/// Order in which `id` was mapped (0, 1, ...).
	long mappedOrder(LandmarkId id) const { return var_of_.at(id).value; }
	Eigen::Vector2d position(LandmarkId id) const;
	std::size_t featureCount() const { return ids_.size(); }
	const std::vector<LandmarkId>& ids() const { return ids_; }

	/// Eq. (3.12)-(3.15): `ids` name the points of `points` (robot or any
	/// local frame; ordered [f1, f2, others...], f1 and f2 supported); ids
	/// not yet mapped are created first, by eq. (3.14).
	MapUpdate updateRelative(const std::vector<LandmarkId>& ids, const PointSet& points);

	/// Joint prior N(points, points.cov) on features given in the map frame;
	/// unmapped ids are created at their given position.
	MapUpdate updateAnchor(const std::vector<LandmarkId>& ids, const PointSet& points);

	/// Takes back `update`; the features it created stay mapped but become
	/// unsupported until an update informs them again.
	void withdraw(const MapUpdate& update);

	/// Evaluate every relative update's Jacobian at one linearisation point
	/// per feature, shared by all updates: the feature's position when it
	/// was created, moved to the current estimate only by relinearise().
	/// Off (the book): each update is linearised at the estimate of its
	/// time. A relative update cannot see a rigid motion of its features
	/// (its Jacobian's null space holds the rotation and translation of the
	/// point where it was evaluated), but updates evaluated at different
	/// points have different null spaces, and together they inform the
	/// rotation of a region that no measurement observed: spurious
	/// information, the inconsistency that first-estimates Jacobians remove
	/// from EKF SLAM (Huang, Mourikis and Roumeliotis, IJRR 2010). With one
	/// point per feature, all updates share one null space. On
	/// configs/sim/long_gap.ini a region's orientation claimed 2.2 deg after
	/// 200 steps where the error was 9 deg (relinearising every 200 steps
	/// reset it to 3.4 deg each time).
	void shareLinearisationPoints(bool share) { share_points_ = share; }

	/// Keep every update's measurement (ids, z and its covariance), so that
	/// relinearise() can evaluate the relative ones again and cost() can
	/// weigh them all. Off by default (the book's EIF never revisits an
	/// update).
	void keepRelativeTerms(bool keep) { keep_terms_ = keep; }
	/// Re-evaluates kept relative updates, eq. (3.15), at the current
	/// estimate (with shared points, all features' points move to the
	/// current estimate first): the old term is subtracted and the
	/// measurement added again
	/// with H_map and its Jacobian at the current estimate (a Gauss-Newton
	/// step of the static map problem; the sparsity pattern is unchanged).
	/// Only the terms whose features' relative geometry moved since their
	/// linearisation by more than `threshold_m` (the largest change of a
	/// feature's offset from the term's f1; H_map is invariant to a common
	/// translation, so a translated cluster needs none); 0 = all terms.
	/// Returns the number of terms relinearised.
	std::size_t relinearise(double threshold_m = 0);
	/// Gauss-Newton on the static map: up to `passes` relinearise() calls,
	/// each followed by recover(reference), stopping at the first that
	/// relinearises nothing. A pass that raises cost() by more than 0.1%
	/// is taken back (its terms and shared points restored, the map
	/// recovered as before it) and ends the iteration: undamped
	/// Gauss-Newton can overshoot where the relative geometry is far from
	/// linear (reference pairs 0.2 m apart on MRCLAM: on robot 3 without
	/// IDs one pass took the cost from 271 to 633, four more threw a feature
	/// 990 m away and D-SLAM stopped as diverged). Returns the number of
	/// terms relinearised in the passes kept.
	std::size_t relineariseUntilSettled(double threshold_m, int passes, const Eigen::Vector2d& reference);
	/// Relinearisation passes taken back so far.
	std::size_t rejectedPasses() const { return rejected_passes_; }
	/// The map's nonlinear least-squares cost at the current estimate: the
	/// sum over kept updates in force of |z - h(x)|^2 weighed by R^-1
	/// (relative updates, eq. 3.13, and anchors). 0 unless terms are kept.
	double cost();

	/// The features `ids`' positions, stacked [x1, y1, x2, y2, ...].
	Eigen::VectorXd positions(const std::vector<LandmarkId>& ids) const;
	/// How far the relative geometry of `ids` has moved since they stood at
	/// `then` (stacked, as positions()): the largest change of a feature's
	/// offset from the first. A common translation does not count.
	double relativeChangeSince(const std::vector<LandmarkId>& ids, const Eigen::VectorXd& then) const;

	/// x = I^-1 i (eq. 3.24), reordering about `robot_xy` when needed.
	void recover(const Eigen::Vector2d& robot_xy);
	/// Joint covariance of the features `ids` (eq. 3.25).
	Eigen::MatrixXd covariance(const std::vector<LandmarkId>& ids);

	/// Every feature with its marginal covariance.
	std::vector<LandmarkEstimate> landmarks();

	/// The map's state (features only, eq. 3.10) with its information
	/// matrix, at the last recovery.
	StateInformation stateInformation() const;

	SparseInformationCore& core() { return core_; }
	const SparseInformationCore& core() const { return core_; }

   private:
	/// A new variable at `position`, linearised at `shared_point` while
	/// points are shared.
	VarId createFeature(LandmarkId id, const Eigen::Vector2d& position, const Eigen::Vector2d& shared_point);
	std::vector<VarId> variables(const std::vector<LandmarkId>& ids) const;
	void markSupported(const std::vector<LandmarkId>& ids);

	/// An update's measurement: z_map with R_map, eq. (3.8)-(3.9), or an
	/// anchor's points with their covariance, held as its Cholesky factor:
	/// factored once, for every relinearisation and cost() after.
	struct Measurement
	{
		Eigen::VectorXd z;
		Eigen::LLT<Eigen::MatrixXd> R_factor;
	};
	static Measurement measurement(Eigen::VectorXd z, const Eigen::MatrixXd& R);
	static Measurement relativeMeasurement(const PointSet& points);
	/// A kept update: its measurement and the term now applied.
	struct KeptTerm
	{
		std::vector<VarId> vars;  ///< the update's features, in its order
		Measurement measurement;
		UpdateTerm term;
		Eigen::VectorXd linearised_at;	///< where `term` was evaluated (the features' stacked points)
		bool anchor = false;			///< linear (H = I): never relinearised
		bool active = true;
	};
	/// Eq. (3.13)-(3.15) on the features `vars`, linearised at `x_lin` (their
	/// stacked linearisation points), `x_now` their current estimate.
	UpdateTerm relativeTerm(const std::vector<VarId>& vars, const Measurement& m, const Eigen::VectorXd& x_lin,
							const Eigen::VectorXd& x_now);
	/// The current positions of a kept term's features, stacked as
	/// positions() stacks them, read from `state` (the core's recovered
	/// state) into `out`: what cost(), relinearisation and undo() read.
	void termPoints(const KeptTerm& t, const Eigen::VectorXd& state, Eigen::VectorXd& out) const;
	/// Feature `v`'s position in `state` (the core's recovered state).
	Eigen::Vector2d pointIn(const Eigen::VectorXd& state, VarId v) const;
	/// A relinearisation pass as applied: the terms it changed with their
	/// old linearisation points, and the shared points before it.
	struct Pass
	{
		std::vector<std::pair<std::size_t, Eigen::VectorXd>> changed;
		std::vector<Eigen::Vector2d> shared_before;
	};
	Pass relinearisePass(double threshold_m);
	/// Restores the terms and shared points `pass` changed.
	void undo(const Pass& pass);
	/// relativeChangeSince() between two stacked position vectors.
	static double relativeChange(const Eigen::VectorXd& now, const Eigen::VectorXd& then);
	/// Where an update on `ids` is linearised: their shared points, or their
	/// current estimate.
	Eigen::VectorXd linearisationPoints(const std::vector<LandmarkId>& ids) const;

	SparseInformationCore core_;
	bool keep_terms_ = false;
	std::vector<KeptTerm> terms_;
	std::size_t rejected_passes_ = 0;
	std::unordered_map<LandmarkId, VarId> var_of_;
	std::vector<LandmarkId> ids_;  ///< in order of creation (= variable order)
	std::unordered_set<LandmarkId> unsupported_;
	bool share_points_ = false;
	std::vector<Eigen::Vector2d> shared_point_;	 ///< per feature, in variable order
};

}  // namespace esif::relative
