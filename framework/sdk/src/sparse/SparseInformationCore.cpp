#include <esif/core/Errors.h>
#include "sparse/FreshCholesky.h"
#include "sparse/IncrementalCholesky.h"
#include "sparse/PatternExport.h"
#include "sparse/PcgSolver.h"
#include <esif/sparse/SparseInformationCore.h>
#include "sparse/SparseInverse.h"

#include <chrono>
#include <stdexcept>

namespace esif
{
namespace
{
/// Adds the wall time of its scope to a counter.
class ScopedTimer
{
   public:
	explicit ScopedTimer(double& total_s) : total_s_(total_s), start_(std::chrono::steady_clock::now()) {}
	~ScopedTimer() { total_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

   private:
	double& total_s_;
	std::chrono::steady_clock::time_point start_;
};

std::unique_ptr<RecoverySolver> makeSolver(const SparseRecoveryParams& params, SparseCounters& counters,
										   CholmodCommon& common)
{
	switch (params.recovery)
	{
		case RecoveryMethod::Pcg:
			return std::make_unique<PcgSolver>(params, counters, common);
		case RecoveryMethod::FreshCholesky:
			return std::make_unique<FreshCholesky>(params, counters, common);
		case RecoveryMethod::IncrementalCholesky:
			break;
	}
	return std::make_unique<IncrementalCholesky>(params, counters, common);
}
}  // namespace

struct SparseInformationCore::Solver
{
	CholmodCommon cholmod;	// before every CHOLMOD object: destroyed last
	std::unique_ptr<RecoverySolver> method;
};

SparseInformationCore::SparseInformationCore(const SparseRecoveryParams& params)
	: params_(params), solver_(std::make_unique<Solver>())
{
	solver_->method = makeSolver(params_, counters_, solver_->cholmod);
}

SparseInformationCore::~SparseInformationCore() = default;

VarId SparseInformationCore::addPoint(const Eigen::Vector2d& initial)
{
	ScopedTimer t(counters_.update_time_s);
	return info_.addVariable(VarKind::Point2, initial);
}

VarId SparseInformationCore::addPose(const Eigen::Vector3d& initial)
{
	ScopedTimer t(counters_.update_time_s);
	return info_.addVariable(VarKind::Pose2, initial);
}

UpdateTerm SparseInformationCore::addMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J,
												 const Eigen::MatrixXd& R, const Eigen::VectorXd& innovation)
{
	return timedUpdate(vars, [&] { return info_.addMeasurement(vars, J, R, innovation); });
}

UpdateTerm SparseInformationCore::addMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J,
												 const Eigen::LLT<Eigen::MatrixXd>& R_factor,
												 const Eigen::VectorXd& innovation)
{
	return timedUpdate(vars, [&] { return info_.addMeasurement(vars, J, R_factor, innovation); });
}

UpdateTerm SparseInformationCore::addInformationMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J,
															const Eigen::MatrixXd& information,
															const Eigen::VectorXd& innovation)
{
	return timedUpdate(vars, [&] { return info_.addInformationMeasurement(vars, J, information, innovation); });
}

UpdateTerm SparseInformationCore::timedUpdate(const std::vector<VarId>& vars, const std::function<UpdateTerm()>& apply)
{
	ScopedTimer t(counters_.update_time_s);
	settleEstimates(vars);
	UpdateTerm term = apply();
	noteUpdate(term);
	return term;
}

void SparseInformationCore::withdraw(const UpdateTerm& term)
{
	ScopedTimer t(counters_.update_time_s);
	info_.subtract(term);
	solver_->method->noteWithdrawal();
}

void SparseInformationCore::addPrior(VarId v, const Eigen::VectorXd& mean, const Eigen::MatrixXd& information)
{
	ScopedTimer t(counters_.update_time_s);
	noteUpdate(info_.addPrior(v, mean, information));
}

void SparseInformationCore::noteUpdate(const UpdateTerm& term)
{
	solver_->method->noteUpdate(info_, term);
}

void SparseInformationCore::refresh()
{
	ScopedTimer t(counters_.factor_time_s);
	try
	{
		solver_->method->refresh(info_, reference_);
	}
	catch (...)
	{
		on_demand_ = false;	 // no factor to read: the estimate stays the last one written
		throw;
	}
	refreshed_dim_ = info_.scalarDim();
}

const Eigen::VectorXd& SparseInformationCore::recoverState()
{
	refresh();
	ScopedTimer t(counters_.recovery_time_s);
	Eigen::VectorXd x = info_.estimate();
	solver_->method->solveState(info_, x);
	if (!x.allFinite()) throw NumericalError("sparse recovery: the recovered state is not finite");
	info_.setEstimate(x);
	on_demand_ = false;
	return info_.estimate();
}

void SparseInformationCore::recoverStateOnDemand()
{
	refresh();
	if (!solver_->method->solvesStatePartially())
	{
		recoverState();
		return;
	}
	on_demand_ = true;
}

const Eigen::VectorXd& SparseInformationCore::state()
{
	if (!on_demand_) return info_.estimate();
	// The whole back substitution of the factor as of the last refresh;
	// variables added since keep their initial values.
	ScopedTimer t(counters_.recovery_time_s);
	Eigen::VectorXd solved = info_.estimate();
	solver_->method->solveState(info_, solved);
	Eigen::VectorXd x = info_.estimate();
	x.head(refreshed_dim_) = solved.head(refreshed_dim_);
	if (!x.allFinite()) throw NumericalError("sparse recovery: the recovered state is not finite");
	info_.setEstimate(x);
	on_demand_ = false;
	return info_.estimate();
}

bool SparseInformationCore::readsFactor(VarId v) const
{
	return on_demand_ && info_.offset(v) + info_.dim(v) <= refreshed_dim_;
}

Eigen::VectorXd SparseInformationCore::estimate(VarId v) const
{
	if (v.value < 0 || v.value >= info_.variableCount())
		throw std::out_of_range("SparseInformationCore::estimate: no variable " + std::to_string(v.value));
	if (!readsFactor(v)) return info_.estimate().segment(info_.offset(v), info_.dim(v));
	// The solver keeps what it solved (PartialBackSubstitution): a cache, so
	// reading stays a const operation.
	const Eigen::VectorXd x = solver_->method->solveStateAt(info_.scalarIndices({v}));
	if (!x.allFinite())
		throw NumericalError("sparse recovery: the recovered estimate of " + info_.describeScalar(info_.offset(v)) +
							 " is not finite");
	return x;
}

void SparseInformationCore::settleEstimates(const std::vector<VarId>& vars)
{
	for (const VarId v : vars)
		if (readsFactor(v)) info_.setEstimate(v, estimate(v));
}

Eigen::MatrixXd SparseInformationCore::covariance(const std::vector<VarId>& vars)
{
	refresh();
	ScopedTimer t(counters_.recovery_time_s);
	const Eigen::MatrixXd P = solver_->method->solveCovarianceBlock(info_, info_.scalarIndices(vars));
	if (!P.allFinite()) throw NumericalError("sparse recovery: a recovered covariance is not finite");
	return 0.5 * (P + P.transpose());
}

std::vector<Eigen::MatrixXd> SparseInformationCore::marginalCovariances()
{
	refresh();
	ScopedTimer t(counters_.recovery_time_s);
	cholmod_factor* L = solver_->method->choleskyFactor();
	SparseCounters scratch;  // a one-off factorisation, not a reordering of the method's own
	std::unique_ptr<FreshCholesky> fresh;
	if (!L)
	{
		fresh = std::make_unique<FreshCholesky>(params_, scratch, solver_->cholmod);
		fresh->refresh(info_, reference_);
		L = fresh->choleskyFactor();
	}
	const SparseInverse Z(*L, solver_->cholmod);
	std::vector<Eigen::MatrixXd> out;
	out.reserve(info_.variableCount());
	for (int v = 0; v < info_.variableCount(); ++v) out.push_back(Z.block(info_.scalarIndices({VarId{v}})));
	return out;
}

StateInformation SparseInformationCore::stateInformation(const std::function<StateVariable(VarId)>& describe) const
{
	StateInformation out;
	for (int v = 0; v < info_.variableCount(); ++v)
	{
		out.variables.push_back(describe(VarId{v}));
		if (out.variables.back().dim() != info_.dim(VarId{v}))
			throw std::logic_error("SparseInformationCore::stateInformation: variable " + std::to_string(v) +
								   " described with the wrong dimension");
	}
	out.mean = info_.estimate();
	if (on_demand_)
		for (int v = 0; v < info_.variableCount(); ++v)
			out.mean.segment(info_.offset(VarId{v}), info_.dim(VarId{v})) = estimate(VarId{v});
	out.information = toEigenSparse(info_.matrix());
	return out;
}

InformationPattern SparseInformationCore::pattern()
{
	InformationPattern out;
	out.information = toEigenSparse(info_.matrix());
	if (info_.scalarDim() == 0) return out;
	refresh();
	const int n = info_.scalarDim();
	const char* order = params_.recovery == RecoveryMethod::FreshCholesky ? "AMD ordering"
																		  : reorderingTitle(params_.reordering);
	if (cholmod_factor* L = solver_->method->choleskyFactor())
	{
		out.factor = toEigenSparse(*L, n, solver_->cholmod);
		out.factor_order = std::string("Cholesky factor, ") + order;
	}
	else if (const LowerCsc* Lic = solver_->method->incompleteFactor())
	{
		out.factor = toEigenSparse(*Lic, n);
		out.factor_order = std::string("incomplete Cholesky preconditioner, ") + order;
	}
	return out;
}

SparseCounters SparseInformationCore::counters() const
{
	SparseCounters c = counters_;
	c.information_nnz = info_.matrix().nonZeros();
	c.factor_nnz = solver_->method->factorNonZeros();
	return c;
}

}  // namespace esif
