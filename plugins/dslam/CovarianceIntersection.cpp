#include "CovarianceIntersection.h"

#include <esif/core/Errors.h>
#include <esif/models/Se2.h>

#include <Eigen/Cholesky>
#include <boost/math/tools/minima.hpp>

#include <stdexcept>

namespace esif::dslam
{
namespace
{
Eigen::MatrixXd inverseSpd(const Eigen::MatrixXd& P, const char* which)
{
	const Eigen::LLT<Eigen::MatrixXd> llt(P);
	if (llt.info() != Eigen::Success)
		throw NumericalError(std::string("covariance intersection: ") + which + " covariance not positive definite");
	return llt.solve(Eigen::MatrixXd::Identity(P.rows(), P.cols()));
}
}  // namespace

CiResult covarianceIntersection(const GaussianState& a, const GaussianState& b)
{
	if (a.mean.size() != b.mean.size() || a.mean.size() < 3)
		throw std::invalid_argument("covariance intersection: the two states differ in size");
	Eigen::VectorXd xb = b.mean;
	xb(2) = a.mean(2) + wrapAngle(b.mean(2) - a.mean(2));

	const Eigen::MatrixXd Ia = inverseSpd(a.cov, "first"), Ib = inverseSpd(b.cov, "second");
	const auto robotTrace = [&](double w)
	{
		const Eigen::LLT<Eigen::MatrixXd> llt(w * Ia + (1 - w) * Ib);
		return llt.solve(Eigen::MatrixXd::Identity(Ia.rows(), 3)).topRows<3>().trace();
	};
	// Brent's method on [0, 1]: the trace is smooth in w; 1e-6 in w is far
	// below what changes the fused estimate noticeably.
	constexpr int kBits = 20;
	const double w = boost::math::tools::brent_find_minima(robotTrace, 0.0, 1.0, kBits).first;

	// Eq. (3.21).
	const Eigen::LLT<Eigen::MatrixXd> llt(w * Ia + (1 - w) * Ib);
	if (llt.info() != Eigen::Success) throw NumericalError("covariance intersection: fused information singular");
	CiResult out;
	out.omega = w;
	out.fused.cov = llt.solve(Eigen::MatrixXd::Identity(Ia.rows(), Ia.cols()));
	out.fused.cov = 0.5 * (out.fused.cov + out.fused.cov.transpose()).eval();
	out.fused.mean = llt.solve(w * Ia * a.mean + (1 - w) * Ib * xb);
	out.fused.mean(2) = wrapAngle(out.fused.mean(2));
	return out;
}

GaussianState robotMarginal(const GaussianState& s) { return leadingMarginal(s, 3); }

GaussianState leadingMarginal(const GaussianState& s, Eigen::Index n)
{
	return {s.mean.head(n), s.cov.topLeftCorner(n, n)};
}

GaussianState withLeadingMarginal(const GaussianState& s, const GaussianState& lead)
{
	const Eigen::Index n = s.mean.size(), l = lead.mean.size(), m = n - l;
	const Eigen::LLT<Eigen::MatrixXd> Pll(s.cov.topLeftCorner(l, l));
	if (Pll.info() != Eigen::Success) throw NumericalError("leading marginal: covariance not positive definite");
	const Eigen::MatrixXd K = Pll.solve(s.cov.topRightCorner(l, m)).transpose();	// P_fl P_ll^-1
	Eigen::VectorXd dl = lead.mean - s.mean.head(l);
	dl(2) = wrapAngle(dl(2));
	GaussianState out;
	out.mean = s.mean;
	out.mean.head(l) += dl;
	out.mean(2) = wrapAngle(out.mean(2));
	out.mean.tail(m) += K * dl;
	out.cov.resize(n, n);
	out.cov.topLeftCorner(l, l) = lead.cov;
	out.cov.bottomLeftCorner(m, l) = K * lead.cov;
	out.cov.topRightCorner(l, m) = out.cov.bottomLeftCorner(m, l).transpose();
	out.cov.bottomRightCorner(m, m) =
		s.cov.bottomRightCorner(m, m) - K * s.cov.topRightCorner(l, m) + K * lead.cov * K.transpose();
	out.cov = 0.5 * (out.cov + out.cov.transpose()).eval();
	return out;
}

}  // namespace esif::dslam
