#include <esif/association/Chi2.h>

#include <boost/math/distributions/chi_squared.hpp>

#include <limits>
#include <stdexcept>

namespace esif
{
namespace
{
boost::math::chi_squared_distribution<double> chiSquared(int dof, const char* who)
{
	if (dof < 1) throw std::invalid_argument(std::string(who) + ": dof must be >= 1");
	return boost::math::chi_squared_distribution<double>(dof);
}
}  // namespace

double chi2Cdf(double x, int dof)
{
	const auto chi2 = chiSquared(dof, "chi2Cdf");
	return x <= 0 ? 0.0 : boost::math::cdf(chi2, x);
}

double chi2Quantile(double p, int dof)
{
	const auto chi2 = chiSquared(dof, "chi2Quantile");
	if (!(p > 0 && p < 1)) throw std::invalid_argument("chi2Quantile: p must be in (0, 1)");
	return boost::math::quantile(chi2, p);
}

double chi2GateBound(double p, int dof)
{
	return p >= 1 ? std::numeric_limits<double>::infinity() : chi2Quantile(p, dof);
}

}  // namespace esif
