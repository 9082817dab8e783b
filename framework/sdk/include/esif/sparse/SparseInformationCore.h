#pragma once
/// \file SparseInformationCore.h
/// The sparse information-form core shared by the D-SLAM, D-SLAM local map
/// joining and SLSJF plugins (book Ch. 3-5): variables (points, poses),
/// additive EIF updates, eq. (3.15)/(5.6)/(5.9), and recovery of the state
/// (3.24), of chosen covariance blocks (3.25) and of every variable's
/// marginal covariance (sparse inverse), by the method chosen in
/// SparseRecoveryParams. Owns the one cholmod_common of its factors.
///
/// Typical step: add the new variables (with initial estimates), add the
/// step's measurements, setReferencePoint(robot position), recoverState(),
/// then covariance({...}) for the variables near the robot.

#include <esif/core/InformationPattern.h>
#include <esif/core/StateInformation.h>
#include <esif/sparse/InformationForm.h>
#include <esif/sparse/SparseCounters.h>
#include <esif/sparse/SparseRecoveryParams.h>

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

namespace esif
{
class SparseInformationCore
{
   public:
	explicit SparseInformationCore(const SparseRecoveryParams& params = {});
	~SparseInformationCore();
	SparseInformationCore(const SparseInformationCore&) = delete;
	SparseInformationCore& operator=(const SparseInformationCore&) = delete;

	/// New point variable with zero information, initial estimate `initial`.
	VarId addPoint(const Eigen::Vector2d& initial);
	/// New pose variable (x, y, theta) with zero information.
	VarId addPose(const Eigen::Vector3d& initial);

	/// EIF update, eq. (3.15): Jacobian J over `vars` (columns stacked in
	/// that order), measurement covariance R, innovation z - h(x^) at the
	/// current estimate (angles wrapped by the caller).
	/// Returns the update as applied, for a later withdraw().
	UpdateTerm addMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J, const Eigen::MatrixXd& R,
							  const Eigen::VectorXd& innovation);
	/// The same with R given by its Cholesky factor (InformationForm.h).
	UpdateTerm addMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J,
							  const Eigen::LLT<Eigen::MatrixXd>& R_factor, const Eigen::VectorXd& innovation);
	/// EIF update with the measurement's information matrix instead of its
	/// covariance (eq. 5.9 with a local map's information, never inverted).
	UpdateTerm addInformationMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J,
										 const Eigen::MatrixXd& information, const Eigen::VectorXd& innovation);
	/// Takes back an update returned by addMeasurement() (book Sec. 3.4.1:
	/// D-SLAM withdraws the last map update when the next scan is not
	/// admissible). The next recovery factors afresh.
	void withdraw(const UpdateTerm& term);
	/// Prior N(mean, information^-1) on one variable (e.g. the map anchor).
	void addPrior(VarId v, const Eigen::VectorXd& mean, const Eigen::MatrixXd& information);

	/// Where the robot (or the reference feature) is: reorderings put the
	/// variables nearest to it last.
	void setReferencePoint(const Eigen::Vector2d& p) { reference_ = p; }

	/// x = I^-1 i, eq. (3.24); becomes the new linearisation point. Throws
	/// NumericalError (never returns NaN) if I is not numerically positive
	/// definite, naming the variable where it failed.
	const Eigen::VectorXd& recoverState();
	/// The same recovery with the back substitution (eq. 3.37) left to the
	/// reads: estimate(v) solves v and its elimination-tree ancestors when
	/// first read and keeps them until the factor changes, so a filter that
	/// reads a few variables before its next update (SLSJF: the next local
	/// map's features) pays for their paths, not for all of L. Every read is
	/// exact: until the next recoverState(), a variable's estimate is x = I^-1 i
	/// of the information as of the last refresh (a covariance() after an
	/// update refreshes), as a recoverState() there would give. Methods
	/// without a complete simplicial factor recover the whole state here.
	void recoverStateOnDemand();
	/// Current estimate of all variables (last recovery; initial values for
	/// variables added since); completes an on-demand recovery first.
	const Eigen::VectorXd& state();
	/// Current estimate of one variable.
	Eigen::VectorXd estimate(VarId v) const;

	/// Joint covariance of `vars` (rows/columns stacked in that order), from
	/// covariance columns, eq. (3.25).
	Eigen::MatrixXd covariance(const std::vector<VarId>& vars);
	/// Marginal covariance of every variable (2x2 points, 3x3 poses), in
	/// order of creation, from the sparse inverse on the Cholesky factor's
	/// pattern (SparseInverse.h). Methods without a complete factor (PCG)
	/// make one fresh factorisation for it.
	std::vector<Eigen::MatrixXd> marginalCovariances();

	/// Sparsity of I (natural order) and of the method's current factor (its
	/// own order), brought up to date first; for pictures and pattern tests.
	InformationPattern pattern();

	/// The estimate (last recovery) and I as a StateInformation, each
	/// variable (in order of creation) named by `describe`, which must give
	/// it its own dimension (2 points, 3 poses).
	StateInformation stateInformation(const std::function<StateVariable(VarId)>& describe) const;

	/// Counters with the current non-zeros of I and of the factor.
	SparseCounters counters() const;

	const InformationForm& information() const { return info_; }
	const SparseRecoveryParams& params() const { return params_; }
	int variableCount() const { return info_.variableCount(); }
	int stateDim() const { return info_.scalarDim(); }

	/// Brings the factor up to date with the updates so far: under an
	/// on-demand recovery, estimates read after it are x = I^-1 i of the
	/// information as of now (recoverState(), covariance() and
	/// marginalCovariances() refresh by themselves).
	void refresh();

   private:
	/// An update of the information form (`apply`) on `vars`: their on-demand
	/// estimates settled first, its time counted, the solver told.
	UpdateTerm timedUpdate(const std::vector<VarId>& vars, const std::function<UpdateTerm()>& apply);
	void noteUpdate(const UpdateTerm& term);
	/// Under an on-demand recovery, whether v's estimate comes from the factor.
	bool readsFactor(VarId v) const;
	/// Writes the on-demand estimates of `vars` into the information form,
	/// where an update reads its linearisation point.
	void settleEstimates(const std::vector<VarId>& vars);

	/// CHOLMOD's workspace and the recovery method (RecoverySolver.h),
	/// private to the SDK: no plugin sees cholmod.h.
	struct Solver;

	SparseRecoveryParams params_;
	SparseCounters counters_;
	InformationForm info_;
	std::unique_ptr<Solver> solver_;
	Eigen::Vector2d reference_ = Eigen::Vector2d::Zero();
	bool on_demand_ = false;  ///< recoverStateOnDemand() since the last whole recovery
	int refreshed_dim_ = 0;   ///< scalars in the factor at the last refresh
};

}  // namespace esif
