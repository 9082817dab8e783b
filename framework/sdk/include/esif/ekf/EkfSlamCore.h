#pragma once
/// \file EkfSlamCore.h
/// Full-covariance EKF SLAM over a robot pose and 2-D point features (book
/// Sec. 1.2.1, eq. 1.1-1.10). The state is [x, y, phi, x1, y1, x2, y2, ...].
///
/// Costs: prediction O(N) (only the robot rows of P change), an update with m
/// measurements O(m N^2) (the observation Jacobian touches 5 columns per
/// measurement, so P H^T is formed from those columns only and P is updated
/// by one symmetric rank-2m product), adding a landmark O(N) amortised.
/// Used by the EKF plugin, D-SLAM's local localisation and local-map builders.

#include <esif/core/StepInput.h>
#include <esif/models/RangeBearingModel.h>
#include <esif/models/Se2.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace esif
{
/// When and how far the EKF update is iterated (iterated EKF: Gauss-Newton
/// on the scan's posterior). The update is first linearised at the prior
/// mean x0 (the plain EKF, eq. 1.9-1.10), giving x1. Its linearisation error
/// is the largest, over the scan's measurements, squared Mahalanobis norm
/// (sensor noise R) of h(x1) - h(x0) - H(x0) (x1 - x0): how far the linear
/// model the update trusted misses the true one at the corrected state.
/// Above min_linearisation_error_d2 the model is relinearised at the last
/// estimate, at most max_iterations linearisations in all, until an
/// iteration moves no state entry by more than `tolerance` [m or rad].
///
/// Why: after a long stretch of dead reckoning the prior mean can be metres
/// off, and the Jacobians taken there (the bearing's scales as 1/range)
/// both misplace the correction and shrink P by the wrong amount: the
/// inconsistency of Sec. 1.3.3, which grows with the heading uncertainty.
/// Why not always: relinearising an update whose linearisation is already
/// good changes the estimate by far less than the noise, except along the
/// directions the prior barely constrains (the map's absolute pose after a
/// gap), where the Gaussian prior of an EKF is itself only a linearisation;
/// there, iterating every scan drifts the estimate (measured on long_gap:
/// metres of drift over the crossings).
struct IteratedUpdate
{
	int max_iterations = 1;	 ///< 1 = the plain EKF update
	double min_linearisation_error_d2 = 1.0;
	/// [m, rad]: a micrometre, 1e-5 of the book's range sigma (0.1 m).
	double tolerance = 1e-6;
};

/// Where predict(), update() and addLandmark() evaluate their Jacobians.
///
/// Current: the textbook EKF (eq. 1.8-1.10), every Jacobian at the latest
/// estimate. Jacobians of one state taken at different estimates of it (the
/// robot pose before and after an update, a landmark as it moves) no longer
/// share the null space of the true model: the linearised system then
/// "observes" the global rotation, which no relative measurement can, and
/// the filter gains spurious information about the heading and becomes
/// over-confident (Sec. 1.3.3; Huang, Mourikis, Roumeliotis, ICRA 2008 and
/// IJRR 2010).
///
/// FirstEstimates: the first-estimates Jacobians (FEJ) of Huang et al.,
/// with the robot at its prior (propagated) estimate x_{k|k-1}, the value
/// the last predict() produced (after setState() or at the start: that state):
///  - propagation from k to k+1: F = [I, J (p_{k+1|k} - p_{k|k-1}); 0, 1],
///    J = [0 -1; 1 0] (the updated p_{k|k} of the textbook replaced by the
///    prior p_{k|k-1}); the noise Jacobian stays at x_{k|k}, it does not
///    enter the null space;
///  - measurement of landmark i at step k: H (range-bearing, robot and
///    landmark columns alike) at the robot's x_{k|k-1} and the landmark's
///    first estimate, the value addLandmark() gave it;
///  - initialising a landmark: its position p_L from the current x_{k|k}
///    (the best estimate, which becomes its first estimate), its Jacobian
///    with respect to the robot [I, J (p_L - p_{k|k-1})], i.e. taken about
///    the robot's prior as well.
/// Innovations and predicted measurements still use the current estimate.
/// With these points every Jacobian maps the rotation direction
/// n = [J p_R; 1; J p_L1; J p_L2; ...] of the linearisation points onto its
/// successor (F n_k = n_{k+1}, the new landmark's row of the augmentation
/// is J p_L) and H n = 0: the linearised system has the 3-dimensional
/// unobservable subspace (translation and rotation) of the nonlinear one,
/// and a prior variance along n is carried through unchanged.
/// The price: a landmark initialised far from the truth (after a long stretch
/// of dead reckoning) keeps its Jacobians there. For the iterated update
/// see update().
enum class JacobianPoints
{
	Current,
	FirstEstimates
};

/// What one update did.
struct UpdateOutcome
{
	int linearisations = 0;	 ///< 0 without matches, 1 for the plain EKF update
	/// Of the first linearisation (IteratedUpdate), 0 when not iterating.
	double linearisation_error_d2 = 0;
	/// An iterate raised the scan's posterior cost and was not taken.
	bool stopped_uphill = false;
};

class EkfSlamCore
{
   public:
	/// Robot at the origin with zero covariance: the map frame is the initial
	/// robot pose (relative SLAM, Sec. 1.3.1).
	explicit EkfSlamCore(JacobianPoints points = JacobianPoints::Current);

	/// Where the Jacobians are taken, as given at construction.
	JacobianPoints jacobianPoints() const { return points_; }

	/// Prediction step, eq. (1.8): x_r <- x_r (+) u, P_rr <- F P_rr F^T + G Q G^T,
	/// P_rm <- F P_rm. Features are static (eq. 1.2).
	void predict(const OdometryIncrement& u);

	/// One range-bearing measurement associated with an existing landmark.
	struct Match
	{
		std::size_t landmark = 0;  ///< landmark index (0-based, order of creation)
		Eigen::Vector2d z;	///< (range [m], bearing [rad])
		Eigen::Matrix2d R;	///< its covariance
	};

	/// Update step, eq. (1.9)-(1.10), with all `matches` at once, iterated
	/// as `iterated` says (by default not: the plain EKF). Throws
	/// NumericalError if the innovation covariance is not positive definite.
	/// With FirstEstimates the first linearisation uses the FEJ points. Whether
	/// to iterate is decided as without FEJ (the linearisation error is
	/// measured with h's Jacobians at x0: the nonlinearity of h at the scale
	/// of the correction); the iterations relinearise at the iterate, as
	/// Gauss-Newton needs, and give the new mean, but P is updated with the
	/// FEJ linearisation, so that even an iterated update keeps the null
	/// space. Measured on long_gap (12 draws) against P from the last
	/// iterate: landmark ANEES 8.2 against 9.9, and 10.8 against 21.1 on
	/// wrong_ids (20 draws). Even so, FEJ with the iterated update lost the
	/// map in 2 of 50 grid196 draws and 1 of 20 wrong_ids draws (landmark
	/// RMSE 3-13 m), FEJ without it (max_iterations 1) in none; the textbook
	/// EKF with it in none either. Not understood yet.
	UpdateOutcome update(
		const std::vector<Match>& matches, const Pose2& sensor_on_robot, const IteratedUpdate& iterated = {});

	/// Appends a landmark initialised from a measurement at the current pose,
	/// with its full cross-covariance; returns its index. Its value is its
	/// first estimate (JacobianPoints).
	std::size_t addLandmark(const Eigen::Vector2d& z, const Eigen::Matrix2d& R, const Pose2& sensor_on_robot);

	/// Keeps the robot and the landmarks `keep` (indices, in the order given,
	/// which becomes their new order 0, 1, ...) and drops every other
	/// landmark: marginalisation, which in covariance form is deleting rows
	/// and columns. O(k^2) for k kept landmarks. The kept landmarks keep
	/// their first estimates, the robot its prior.
	void retainLandmarks(const std::vector<std::size_t>& keep);

	/// Squared Mahalanobis distance of the difference of landmarks `a` and
	/// `b` from zero, under its covariance P_aa + P_bb - P_ab - P_ba: how far
	/// the estimate is from their being one point (+inf if that covariance
	/// is not positive definite).
	double coincidenceDistance2(std::size_t a, std::size_t b) const;

	/// Conditions the state on landmarks `keep` and `drop` being one point,
	/// then marginalises out `drop` (the landmarks after it move down one
	/// index). The condition is the linear constraint x_keep - x_drop = 0
	/// taken as a measurement without noise (eq. 1.9-1.10 with R = 0), so
	/// the result is exactly the Gaussian posterior given the constraint:
	/// the state the filter would hold had every measurement of both been
	/// associated with one landmark, up to linearisation. O(N^2). Returns
	/// false, changing nothing, if the covariance of their difference is not
	/// positive definite.
	bool mergeLandmarks(std::size_t keep, std::size_t drop);

	/// Replaces the whole state: x = [robot; landmarks], P its covariance
	/// (e.g. a fused estimate). Throws std::invalid_argument on a size
	/// mismatch or an odd landmark part. The FEJ points become the new state
	/// (robot prior = its robot, first estimates = its landmarks): the core
	/// cannot know how the replacement was linearised, and its own values
	/// are the one set of points consistent with it, so the rotation
	/// direction is preserved from here on.
	void setState(const Eigen::VectorXd& x, const Eigen::MatrixXd& P);

	/// Predicted measurement of landmark `i` from the current robot pose, with
	/// the Jacobians update() would use (at the FEJ points with FirstEstimates).
	RangeBearingPrediction predictMeasurement(std::size_t i, const Pose2& sensor_on_robot) const;

	/// Joint covariance H P H^T (2k x 2k) of the predicted measurements of
	/// `landmarks`, without sensor noise: the data-association input. With
	/// the Jacobians of predictMeasurement(), so an association gate tests
	/// the innovation covariance the update will assume.
	Eigen::MatrixXd predictionCovariance(
		const std::vector<std::size_t>& landmarks, const Pose2& sensor_on_robot) const;

	std::size_t landmarkCount() const { return (n_ - 3) / 2; }
	std::size_t stateDim() const { return n_; }
	Pose2 robot() const { return x_.head<3>(); }
	Eigen::Matrix3d robotCov() const { return P_.topLeftCorner<3, 3>(); }
	Eigen::Vector2d landmark(std::size_t i) const { return x_.segment<2>(3 + 2 * i); }
	Eigen::Matrix2d landmarkCov(std::size_t i) const { return P_.block<2, 2>(3 + 2 * i, 3 + 2 * i); }
	/// FEJ points (JacobianPoints): the robot's prior x_{k|k-1} and landmark
	/// `i`'s first estimate.
	Pose2 robotPrior() const { return robot_prior_; }
	Eigen::Vector2d landmarkFirstEstimate(std::size_t i) const { return first_estimates_.at(i); }

	/// State vector and covariance (the leading stateDim() entries).
	Eigen::VectorBlock<const Eigen::VectorXd> state() const { return x_.head(n_); }
	Eigen::Block<const Eigen::MatrixXd> covariance() const { return P_.topLeftCorner(n_, n_); }

   private:
	/// The measurement model of `matches` linearised at the state `at`.
	struct Linearisation
	{
		Eigen::MatrixXd PHt;  ///< P H^T (n x 2m), P the prior
		Eigen::MatrixXd S;	///< H P H^T + R
		Eigen::VectorXd innovation;	 ///< z - h(at) - H (x0 - at), bearings wrapped
		Eigen::LLT<Eigen::MatrixXd> llt;  ///< of S
		Eigen::MatrixXd Wt;	 ///< L^-1 (P H^T)^T, S = L L^T
		std::vector<RangeBearingPrediction> h;	///< per match: h(at) and its Jacobians
	};
	/// With `first_estimates`, `at` must be the prior mean and the Jacobians
	/// are taken at the FEJ points.
	Linearisation linearise(const std::vector<Match>& matches, const Pose2& sensor_on_robot,
							const Eigen::VectorXd& at, bool first_estimates) const;
	/// h of landmark `i` at the state `at`, its Jacobians at `at` or, with
	/// `first_estimates`, at the FEJ points.
	RangeBearingPrediction measurementModel(
		std::size_t i, const Pose2& sensor_on_robot, const Eigen::VectorXd& at, bool first_estimates) const;
	bool useFirstEstimates() const { return points_ == JacobianPoints::FirstEstimates; }
	/// setState() without touching the FEJ points.
	void replaceState(const Eigen::VectorXd& x, const Eigen::MatrixXd& P);
	/// IteratedUpdate's linearisation error of the update from x0 to x1,
	/// `at_x0` the model linearised at x0; always with h's Jacobians at x0.
	double linearisationError(const std::vector<Match>& matches, const Pose2& sensor_on_robot,
							  const Linearisation& at_x0, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1) const;
	/// The prior mean plus the gain of `lin` times its innovation.
	Eigen::VectorXd stateAfter(const Linearisation& lin) const;
	/// The scan's posterior cost (negative log, up to a constant) at the
	/// state x that `lin` gives (stateAfter): prior Mahalanobis distance of
	/// x from the prior mean plus the whitened measurement residuals at x.
	double scanCost(const std::vector<Match>& matches, const Pose2& sensor_on_robot, const Linearisation& lin,
					const Eigen::VectorXd& x) const;
	void reserve(std::size_t dim);
	void symmetrise();

	Eigen::VectorXd x_;	 // capacity >= n_
	Eigen::MatrixXd P_;	 // capacity x capacity, leading n_ x n_ in use
	std::size_t n_ = 3;
	JacobianPoints points_ = JacobianPoints::Current;
	Pose2 robot_prior_ = Pose2::Zero();	 // x_{k|k-1}
	std::vector<Eigen::Vector2d> first_estimates_;	// per landmark
};

}  // namespace esif
