#include <esif/core/Errors.h>
#include <esif/sparse/InformationForm.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <stdexcept>

namespace esif
{
VarId InformationForm::addVariable(VarKind kind, const Eigen::VectorXd& initial)
{
	const int d = varDim(kind);
	if (initial.size() != d)
		throw std::invalid_argument("InformationForm::addVariable: initial estimate has the wrong size");
	if (!initial.allFinite()) throw NumericalError("adding a variable: non-finite initial estimate");
	const VarId v{I_.addBlockVariable(d)};
	kind_.push_back(kind);
	i_.conservativeResize(I_.scalarDim());
	i_.tail(d).setZero();
	x_.conservativeResize(I_.scalarDim());
	x_.tail(d) = initial;
	return v;
}

void InformationForm::checkVars(const std::vector<VarId>& vars, int columns) const
{
	int total = 0;
	for (std::size_t a = 0; a < vars.size(); ++a)
	{
		if (vars[a].value < 0 || vars[a].value >= variableCount())
			throw std::invalid_argument("InformationForm: unknown variable " + std::to_string(vars[a].value));
		for (std::size_t b = 0; b < a; ++b)
			if (vars[a] == vars[b])
				throw std::invalid_argument("InformationForm: variable " + std::to_string(vars[a].value) +
											" listed twice");
		total += dim(vars[a]);
	}
	if (total != columns)
		throw std::invalid_argument("InformationForm: Jacobian columns do not match the variables' dimensions");
}

void InformationForm::checkMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J,
									   const Eigen::MatrixXd& S, const Eigen::VectorXd& innovation) const
{
	checkVars(vars, static_cast<int>(J.cols()));
	if (S.rows() != J.rows() || S.cols() != J.rows() || innovation.size() != J.rows())
		throw std::invalid_argument("InformationForm: measurement J, covariance/information and innovation sizes differ");
	if (!J.allFinite() || !S.allFinite() || !innovation.allFinite())
		throw NumericalError("measurement update: non-finite Jacobian, covariance or innovation");
}

Eigen::VectorXd InformationForm::linearisationPoint(const std::vector<VarId>& vars, Eigen::Index size) const
{
	Eigen::VectorXd x_lin(size);
	int k = 0;
	for (VarId v : vars)
	{
		x_lin.segment(k, dim(v)) = x_.segment(offset(v), dim(v));
		k += dim(v);
	}
	return x_lin;
}

UpdateTerm InformationForm::addMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J,
										   const Eigen::MatrixXd& R, const Eigen::VectorXd& innovation)
{
	checkMeasurement(vars, J, R, innovation);
	return applyFactored(vars, J, Eigen::LLT<Eigen::MatrixXd>(R), innovation);
}

UpdateTerm InformationForm::addMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J,
										   const Eigen::LLT<Eigen::MatrixXd>& R_factor, const Eigen::VectorXd& innovation)
{
	checkMeasurement(vars, J, R_factor.matrixLLT(), innovation);
	return applyFactored(vars, J, R_factor, innovation);
}

UpdateTerm InformationForm::applyFactored(const std::vector<VarId>& vars, const Eigen::MatrixXd& J,
										  const Eigen::LLT<Eigen::MatrixXd>& R_factor, const Eigen::VectorXd& innovation)
{
	if (R_factor.info() != Eigen::Success)
		throw NumericalError("measurement update: covariance R is not positive definite");

	// With R = L L^T: J^T R^-1 J = C C^T for C = (L^-1 J)^T, and
	// J^T R^-1 (z - h + J x^) = C L^-1 (z - h + J x^)   (eq. 3.15).
	const Eigen::VectorXd x_lin = linearisationPoint(vars, J.cols());
	const Eigen::MatrixXd W = R_factor.matrixL().solve(J);
	const Eigen::VectorXd w = R_factor.matrixL().solve(innovation + J * x_lin);
	return applyWhitened(vars, W.transpose(), w);
}

UpdateTerm InformationForm::addInformationMeasurement(const std::vector<VarId>& vars, const Eigen::MatrixXd& J,
													  const Eigen::MatrixXd& information,
													  const Eigen::VectorXd& innovation)
{
	checkMeasurement(vars, J, information, innovation);
	const Eigen::LLT<Eigen::MatrixXd> llt(information);
	if (llt.info() != Eigen::Success)
		throw NumericalError("measurement update: information matrix is not positive definite");

	// With Lambda = L L^T: J^T Lambda J = C C^T for C = J^T L, and
	// J^T Lambda (z - h + J x^) = C L^T (z - h + J x^)   (eq. 5.9).
	const Eigen::VectorXd x_lin = linearisationPoint(vars, J.cols());
	UpdateTerm term{vars, J.transpose() * llt.matrixL(), J.transpose() * (information * (innovation + J * x_lin))};
	// I += J^T Lambda J formed directly rather than as C C^T: where Lambda
	// does not correlate two variables (a zero block, e.g. the independent
	// features of the authors' maps) their block stays exactly zero and is
	// not stored, so non-zeros are counted as the book counts them (Table
	// 5.1: numerical non-zeros). C is kept for the incremental factor.
	const Eigen::MatrixXd H = J.transpose() * (information * J);
	const std::vector<int> start = starts(vars);
	for (std::size_t b = 0; b < vars.size(); ++b)
		for (std::size_t a = b; a < vars.size(); ++a)
		{
			const auto block = H.block(start[a], start[b], dim(vars[a]), dim(vars[b]));
			if (a == b || !block.isZero(0)) I_.addBlock(vars[a].value, vars[b].value, block);
		}
	addToVector(vars, start, term.delta_i);
	return term;
}

std::vector<int> InformationForm::starts(const std::vector<VarId>& vars) const
{
	std::vector<int> start(vars.size());
	for (std::size_t a = 0, k = 0; a < vars.size(); k += dim(vars[a]), ++a) start[a] = static_cast<int>(k);
	return start;
}

void InformationForm::addToVector(const std::vector<VarId>& vars, const std::vector<int>& start,
								  const Eigen::VectorXd& delta_i)
{
	for (std::size_t a = 0; a < vars.size(); ++a)
		i_.segment(offset(vars[a]), dim(vars[a])) += delta_i.segment(start[a], dim(vars[a]));
}

UpdateTerm InformationForm::addPrior(VarId v, const Eigen::VectorXd& mean, const Eigen::MatrixXd& information)
{
	checkVars({v}, static_cast<int>(mean.size()));
	if (information.rows() != mean.size() || information.cols() != mean.size())
		throw std::invalid_argument("InformationForm::addPrior: information matrix has the wrong size");
	if (!mean.allFinite() || !information.allFinite()) throw NumericalError("prior: non-finite mean or information");
	const Eigen::LLT<Eigen::MatrixXd> llt(information);
	if (llt.info() != Eigen::Success) throw NumericalError("prior: information matrix is not positive definite");
	// information = L L^T, so C = L and i += L (L^T mean).
	const Eigen::MatrixXd L = llt.matrixL();
	return applyWhitened({v}, L, L.transpose() * mean);
}

UpdateTerm InformationForm::applyWhitened(const std::vector<VarId>& vars, Eigen::MatrixXd C, const Eigen::VectorXd& w)
{
	const std::vector<int> start = starts(vars);
	addOuterProduct(vars, start, C, 1.0);
	UpdateTerm term{vars, std::move(C), Eigen::VectorXd()};
	term.delta_i = term.C * w;
	addToVector(vars, start, term.delta_i);
	return term;
}

void InformationForm::addOuterProduct(const std::vector<VarId>& vars, const std::vector<int>& start,
									  const Eigen::MatrixXd& C, double sign)
{
	// Only the blocks of the touched variables change. C C^T is formed as
	// one symmetric rank-k product (syrk) and then scattered: one small
	// product per pair of variables cost more in packing than in flops when
	// a whole local map is one term (relinearising D-SLAM map joining on the
	// 10k city, eq. 4.17). H holds n x n doubles for the term's n scalars,
	// at most twice what C itself holds for a full-rank term (a local map).
	const Eigen::Index n = C.rows();
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
	H.selfadjointView<Eigen::Lower>().rankUpdate(C, sign);
	for (std::size_t b = 0; b < vars.size(); ++b)
	{
		const int db = dim(vars[b]);
		// At most 3 x 3 (a pose): on the stack, not one allocation per variable.
		const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3> diagonal =
			H.block(start[b], start[b], db, db).selfadjointView<Eigen::Lower>();
		I_.addBlock(vars[b].value, vars[b].value, diagonal);
		for (std::size_t a = b + 1; a < vars.size(); ++a)
			I_.addBlock(vars[a].value, vars[b].value, H.block(start[a], start[b], dim(vars[a]), db));
	}
}

void InformationForm::subtract(const UpdateTerm& term)
{
	checkVars(term.vars, static_cast<int>(term.C.rows()));
	const std::vector<int> start = starts(term.vars);
	addOuterProduct(term.vars, start, term.C, -1.0);
	for (std::size_t a = 0; a < term.vars.size(); ++a)
		i_.segment(offset(term.vars[a]), dim(term.vars[a])) -= term.delta_i.segment(start[a], dim(term.vars[a]));
}

void InformationForm::setEstimate(const Eigen::VectorXd& x)
{
	if (x.size() != scalarDim()) throw std::invalid_argument("InformationForm::setEstimate: wrong size");
	x_ = x;
}

void InformationForm::setEstimate(VarId v, const Eigen::VectorXd& x)
{
	if (v.value < 0 || v.value >= variableCount() || x.size() != dim(v))
		throw std::invalid_argument("InformationForm::setEstimate: no such variable or wrong size");
	x_.segment(offset(v), dim(v)) = x;
}

std::vector<int> InformationForm::scalarIndices(const std::vector<VarId>& vars) const
{
	std::vector<int> out;
	for (VarId v : vars)
		for (int a = 0; a < dim(v); ++a) out.push_back(offset(v) + a);
	return out;
}

std::string InformationForm::describeScalar(int g) const
{
	const int b = I_.blockOfScalar(g);
	return "variable " + std::to_string(b) + " (" + varKindName(kind_[b]) + ", component " +
		std::to_string(g - I_.blockOffset(b)) + ")";
}

}  // namespace esif
