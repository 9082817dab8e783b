#pragma once
/// \file RecoverySolver.h
/// Interface of a state/covariance recovery method for the information form
/// (book Sec. 3.3): it follows the additive updates, keeps its factor or
/// preconditioner current, and solves I x = b for the state (eq. 3.24) and
/// for covariance columns (eq. 3.25).

#include "sparse/Cholmod.h"
#include <esif/sparse/InformationForm.h>
#include <esif/sparse/LowerCsc.h>

#include <Eigen/Core>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace esif
{
class RecoverySolver
{
   public:
	virtual ~RecoverySolver() = default;

	/// An update I += C C^T, i += delta_i that `info` has just applied. A
	/// solver records what its next refresh needs (e.g. which trailing part
	/// of its ordering was touched).
	virtual void noteUpdate(const InformationForm& info, const UpdateTerm& term) = 0;

	/// `info` has just subtracted an earlier update (I -= C C^T). Factors
	/// follow additive changes only, so the next refresh factors afresh
	/// (Case ii).
	virtual void noteWithdrawal() = 0;

	/// Brings the factor or preconditioner up to date with `info`: partially
	/// when the changes since the last refresh lie in a short trailing part of
	/// the ordering (Case i), otherwise reordering about `reference` and
	/// factoring afresh (Case ii). Throws NumericalError if I is not
	/// (numerically) positive definite.
	virtual void refresh(const InformationForm& info, const Eigen::Vector2d& reference) = 0;

	/// x = I^-1 i, eq. (3.24). On input x is the previous estimate (a warm
	/// start for iterative methods). Requires a refresh after the last update.
	virtual void solveState(const InformationForm& info, Eigen::VectorXd& x) = 0;

	/// Whether solveStateAt() can give part of x = I^-1 i for less than the
	/// whole (a complete simplicial factor can).
	virtual bool solvesStatePartially() const { return false; }
	/// x = I^-1 i at the scalars `scalars` (all factored at the last
	/// refresh), from the factor as of that refresh. Only where
	/// solvesStatePartially().
	virtual Eigen::VectorXd solveStateAt(const std::vector<int>& /*scalars*/)
	{
		throw std::logic_error("this recovery method solves the whole state only");
	}

	/// Columns `scalars` of I^-1, eq. (3.25): scalarDim() x scalars.size().
	virtual Eigen::MatrixXd solveColumns(const InformationForm& info, const std::vector<int>& scalars) = 0;

	/// The joint covariance block of `scalars` (I^-1 restricted to them).
	/// Default: from full covariance columns; methods with a complete factor
	/// may do less work.
	virtual Eigen::MatrixXd solveCovarianceBlock(const InformationForm& info, const std::vector<int>& scalars)
	{
		const Eigen::MatrixXd columns = solveColumns(info, scalars);
		Eigen::MatrixXd P(scalars.size(), scalars.size());
		for (std::size_t a = 0; a < scalars.size(); ++a) P.row(a) = columns.row(scalars[a]);
		return P;
	}

	/// The current complete factor (simplicial or supernodal CHOLMOD), or
	/// null for methods without one.
	virtual cholmod_factor* choleskyFactor() { return nullptr; }

	/// The incomplete factor (positions order) of methods that keep one
	/// instead of a complete factor, else null.
	virtual const LowerCsc* incompleteFactor() const { return nullptr; }

	/// Non-zeros of the factor or preconditioner over the real variables.
	virtual std::size_t factorNonZeros() const = 0;
};

}  // namespace esif
