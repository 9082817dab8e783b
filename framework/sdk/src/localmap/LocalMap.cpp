#include <esif/core/Errors.h>
#include <esif/localmap/LocalMap.h>

#include <Eigen/Cholesky>
#include <set>

namespace esif
{
Eigen::VectorXd LocalMap::state() const
{
	Eigen::VectorXd x(stateDim());
	x.head<3>() = end_pose;
	for (std::size_t i = 0; i < features.size(); ++i) x.segment<2>(3 + 2 * i) = features[i].position;
	return x;
}

Eigen::MatrixXd LocalMap::covarianceMatrix() const
{
	if (covariance) return *covariance;
	const Eigen::LLT<Eigen::MatrixXd> llt(information);
	if (llt.info() != Eigen::Success)
		throw NumericalError("local map " + std::to_string(index) + ": information matrix is not positive definite");
	Eigen::MatrixXd P = llt.solve(Eigen::MatrixXd::Identity(information.rows(), information.cols()));
	return 0.5 * (P + P.transpose());
}

std::size_t LocalMap::featuresInEarlierMaps() const
{
	std::size_t n = 0;
	for (const auto& f : features) n += f.in_earlier_maps;
	return n;
}

namespace
{
/// "" when `m` (n x n) is finite, symmetric to `tolerance` and positive
/// definite, else what is wrong with it.
std::string spdProblem(const Eigen::MatrixXd& m, std::size_t n, double tolerance)
{
	if (m.rows() != static_cast<Eigen::Index>(n) || m.cols() != static_cast<Eigen::Index>(n))
		return "is " + std::to_string(m.rows()) + "x" + std::to_string(m.cols()) + ", expected " +
			std::to_string(n) + "x" + std::to_string(n);
	if (!m.allFinite()) return "has a non-finite entry";
	const double scale = m.cwiseAbs().maxCoeff();
	const double asymmetry = (m - m.transpose()).cwiseAbs().maxCoeff();
	if (asymmetry > tolerance * scale)
		return "is not symmetric (largest difference " + std::to_string(asymmetry) + " against entries up to " +
			std::to_string(scale) + ")";
	const Eigen::MatrixXd sym = 0.5 * (m + m.transpose());
	if (Eigen::LLT<Eigen::MatrixXd>(sym).info() != Eigen::Success) return "is not positive definite";
	return "";
}
}  // namespace

void LocalMap::validate(const std::string& origin, double symmetry_tolerance) const
{
	const std::string where = origin + ": local map " + std::to_string(index) + ": ";
	if (index == 0) throw NumericalError(origin + ": local map index 0 (maps are numbered from 1)");
	if (!end_pose.allFinite()) throw NumericalError(where + "non-finite end pose");
	std::set<LandmarkId> ids;
	for (const auto& f : features)
	{
		if (!f.position.allFinite()) throw NumericalError(where + "feature " + std::to_string(f.id) + " is not finite");
		if (!ids.insert(f.id).second) throw NumericalError(where + "feature " + std::to_string(f.id) + " appears twice");
	}
	if (const auto p = spdProblem(information, stateDim(), symmetry_tolerance); !p.empty())
		throw NumericalError(where + "information matrix " + p);
	if (covariance)
		if (const auto p = spdProblem(*covariance, stateDim(), symmetry_tolerance); !p.empty())
			throw NumericalError(where + "covariance " + p);
	if (link)
	{
		if (!link->delta.allFinite()) throw NumericalError(where + "non-finite link odometry");
		if (const auto p = spdProblem(link->cov, 3, symmetry_tolerance); !p.empty())
			throw NumericalError(where + "link odometry covariance " + p);
	}
}

}  // namespace esif
