#pragma once
/// \file InformationForm.h
/// The information form of a SLAM state over block variables: information
/// vector i, sparse symmetric information matrix I and the current estimate
/// x^ (the linearisation point). Variables are appended with zero
/// information (book Sec. 3.1.3.3); updates are additive, eq. (3.15), (5.9):
///   I += J^T R^-1 J,   i += J^T R^-1 (z - h(x^) + J x^).
/// No marginalisation: rows and columns are never removed.

#include <esif/sparse/BlockSparseMatrix.h>
#include <esif/sparse/SparseTypes.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <string>
#include <vector>

namespace esif
{
/// One additive update in factored form: I += C C^T and i += delta_i on the
/// scalars of `vars` (stacked in that order). C = J^T R^{-1/2} has one column
/// per measurement row; it is what an incremental factor consumes.
struct UpdateTerm
{
	std::vector<VarId> vars;
	Eigen::MatrixXd C;        ///< (sum of dims) x (measurement rows)
	Eigen::VectorXd delta_i;  ///< (sum of dims)
};

class InformationForm
{
   public:
	/// Appends a variable with zero information and initial estimate
	/// `initial` (its linearisation point until a recovery replaces it).
	VarId addVariable(VarKind kind, const Eigen::VectorXd& initial);

	/// EIF update, eq. (3.15): measurement z of the variables `vars` with
	/// Jacobian J (rows x sum of dims, columns stacked in the order of
	/// `vars`), covariance R and innovation z - h(x^) (angles wrapped by the
	/// caller), linearised at the current estimate. Throws NumericalError if
	/// R is not positive definite or an input is not finite.
	UpdateTerm addMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J, const Eigen::MatrixXd& R,
							  const Eigen::VectorXd& innovation);
	/// The same update with R given by its Cholesky factor (R = L L^T),
	/// for a measurement applied again and again (a relinearised update):
	/// R is factored once by its owner. Throws NumericalError if the factor
	/// failed or an input is not finite.
	UpdateTerm addMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J,
							  const Eigen::LLT<Eigen::MatrixXd>& R_factor, const Eigen::VectorXd& innovation);

	/// The same update with the measurement's information matrix Lambda =
	/// R^-1 given instead of R (eq. 5.9 with a local map's information
	/// matrix, as the authors' files hold it): whitened by Lambda's Cholesky
	/// factor, so Lambda is never inverted. Throws NumericalError if Lambda
	/// is not positive definite or an input is not finite.
	UpdateTerm addInformationMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J,
										 const Eigen::MatrixXd& information, const Eigen::VectorXd& innovation);

	/// Absolute information on one variable: a prior N(mean, information^-1)
	/// (J = identity, R^-1 = information in eq. 3.15), e.g. the map anchor.
	UpdateTerm addPrior(VarId v, const Eigen::VectorXd& mean, const Eigen::MatrixXd& information);

	/// Undoes an update this form applied earlier (I -= C C^T, i -= delta_i),
	/// e.g. D-SLAM withdrawing a map update when the next scan is not
	/// admissible (book Sec. 3.4.1). Block non-zeros it created stay
	/// structurally present.
	void subtract(const UpdateTerm& term);

	const BlockSparseMatrix& matrix() const { return I_; }
	const Eigen::VectorXd& vector() const { return i_; }

	/// Current estimate x^, all variables stacked in order of creation.
	const Eigen::VectorXd& estimate() const { return x_; }
	/// Replaces the estimate after a recovery (size must be scalarDim()).
	void setEstimate(const Eigen::VectorXd& x);
	/// Replaces the estimate of one variable (size must be dim(v)).
	void setEstimate(VarId v, const Eigen::VectorXd& x);

	int variableCount() const { return I_.blockCount(); }
	int scalarDim() const { return I_.scalarDim(); }
	VarKind kind(VarId v) const { return kind_[v.value]; }
	int offset(VarId v) const { return I_.blockOffset(v.value); }
	int dim(VarId v) const { return I_.blockDim(v.value); }
	/// (x, y) of the estimate of v: its place in the plane for reorderings.
	Eigen::Vector2d position(VarId v) const { return x_.segment<2>(offset(v)); }

	/// Scalar indices of `vars`, stacked.
	std::vector<int> scalarIndices(const std::vector<VarId>& vars) const;

	/// "variable 12 (point, component 1)" for the scalar index g.
	std::string describeScalar(int g) const;

   private:
	void checkVars(const std::vector<VarId>& vars, int columns) const;
	void checkMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J, const Eigen::MatrixXd& S,
						  const Eigen::VectorXd& innovation) const;
	Eigen::VectorXd linearisationPoint(const std::vector<VarId>& vars, Eigen::Index size) const;
	/// Offset of each of `vars` in a stacked vector over them.
	std::vector<int> starts(const std::vector<VarId>& vars) const;
	void addToVector(const std::vector<VarId>& vars, const std::vector<int>& start, const Eigen::VectorXd& delta_i);
	/// Eq. (3.15) with R's factor, the inputs already checked by the caller.
	UpdateTerm applyFactored(const std::vector<VarId>& vars, const Eigen::MatrixXd& J,
							 const Eigen::LLT<Eigen::MatrixXd>& R_factor, const Eigen::VectorXd& innovation);
	UpdateTerm applyWhitened(const std::vector<VarId>& vars, Eigen::MatrixXd C, const Eigen::VectorXd& rhs);
	/// I += sign C C^T over the blocks of `vars` (C's rows stacked as `start`).
	void addOuterProduct(const std::vector<VarId>& vars, const std::vector<int>& start, const Eigen::MatrixXd& C,
						 double sign);

	BlockSparseMatrix I_;
	Eigen::VectorXd i_;
	Eigen::VectorXd x_;
	std::vector<VarKind> kind_;
};

}  // namespace esif
