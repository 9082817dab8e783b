#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include "sparse/PcgSolver.h"

#include <algorithm>

namespace esif
{
PcgSolver::PcgSolver(const SparseRecoveryParams& params, SparseCounters& counters, CholmodCommon& common)
	: params_(params), counters_(counters), preconditioner_(params, counters, common)
{
}

void PcgSolver::noteUpdate(const InformationForm& info, const UpdateTerm& term)
{
	preconditioner_.noteUpdate(info, term);
}

void PcgSolver::refresh(const InformationForm& info, const Eigen::Vector2d& reference)
{
	preconditioner_.refresh(info, reference);
}

int PcgSolver::solve(const InformationForm& info, const Eigen::VectorXd& b, Eigen::VectorXd& x, const std::string& what)
{
	const auto& I = info.matrix();
	const double b_norm = b.norm(), target = params_.pcg_relative_tolerance * b_norm;
	I.multiply(x, q_);
	r_ = b - q_;
	int it = 0;
	if (b_norm == 0)
		x.setZero();
	else if (r_.norm() > target)
	{
		preconditioner_.apply(r_, z_);
		p_ = z_;
		double rz = r_.dot(z_);
		for (;;)
		{
			if (it == params_.pcg_max_iterations)
				throw NumericalError(what + ": PCG did not converge in " + std::to_string(it) +
									 " iterations (relative residual " + formatNumber(r_.norm() / b_norm) +
									 " > pcg_relative_tolerance " + formatNumber(params_.pcg_relative_tolerance) + ")");
			I.multiply(p_, q_);
			const double curvature = p_.dot(q_);
			// p^T I p <= 0 can only happen if I is not positive definite.
			if (!(curvature > 0))
				throw NumericalError(what + ": information matrix is not positive definite (PCG curvature " +
									 formatNumber(curvature) + ")");
			const double alpha = rz / curvature;
			x += alpha * p_;
			r_ -= alpha * q_;
			++it;
			if (r_.norm() <= target) break;
			preconditioner_.apply(r_, z_);
			const double rz_next = r_.dot(z_);
			p_ = z_ + (rz_next / rz) * p_;
			rz = rz_next;
		}
	}
	if (!x.allFinite()) throw NumericalError(what + ": PCG produced a non-finite solution");
	++counters_.pcg_solves;
	counters_.pcg_iterations_total += it;
	counters_.pcg_iterations_max = std::max<std::size_t>(counters_.pcg_iterations_max, it);
	return it;
}

void PcgSolver::solveState(const InformationForm& info, Eigen::VectorXd& x)
{
	// Eq. (3.24), warm-started from the previous estimate.
	solve(info, info.vector(), x, "sparse recovery (PCG) of the state");
}

Eigen::MatrixXd PcgSolver::solveColumns(const InformationForm& info, const std::vector<int>& scalars)
{
	// Eq. (3.25), each column from zero.
	const int n = info.scalarDim();
	Eigen::MatrixXd out(n, scalars.size());
	Eigen::VectorXd b(n), x(n);
	for (std::size_t j = 0; j < scalars.size(); ++j)
	{
		b.setZero();
		b[scalars[j]] = 1.0;
		x.setZero();
		solve(info, b, x, "sparse recovery (PCG) of a covariance column");
		out.col(j) = x;
	}
	return out;
}

}  // namespace esif
