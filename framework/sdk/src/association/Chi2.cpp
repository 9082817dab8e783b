#include <esif/association/Chi2.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace esif
{
double chi2Cdf(double x, int dof)
{
	if (dof < 1) throw std::invalid_argument("chi2Cdf: dof must be >= 1");
	if (x <= 0) return 0;
	// Closed forms of the regularised incomplete gamma P(dof/2, x/2):
	// even dof: 1 - e^{-x/2} sum_{k<dof/2} (x/2)^k / k!
	// odd dof:  erf(sqrt(x/2)) - e^{-x/2} sum_{k<(dof-1)/2} (x/2)^{k+1/2} / Gamma(k+3/2)
	const double h = 0.5 * x;
	double sum = 0;
	if (dof % 2 == 0)
	{
		double term = 1;
		for (int k = 0; k < dof / 2; ++k)
		{
			if (k > 0) term *= h / k;
			sum += term;
		}
		return 1.0 - std::exp(-h) * sum;
	}
	double term = std::sqrt(h) / std::tgamma(1.5);
	for (int k = 0; k < (dof - 1) / 2; ++k)
	{
		if (k > 0) term *= h / (k + 0.5);
		sum += term;
	}
	return std::erf(std::sqrt(h)) - std::exp(-h) * sum;
}

double chi2Quantile(double p, int dof)
{
	if (!(p > 0 && p < 1)) throw std::invalid_argument("chi2Quantile: p must be in (0, 1)");
	if (dof == 2) return -2.0 * std::log1p(-p);
	double lo = 0, hi = dof + 10.0 * std::sqrt(2.0 * dof) + 50;
	while (chi2Cdf(hi, dof) < p) hi *= 2;
	for (int it = 0; it < 200 && hi - lo > 1e-12 * hi; ++it)
	{
		const double mid = 0.5 * (lo + hi);
		(chi2Cdf(mid, dof) < p ? lo : hi) = mid;
	}
	return 0.5 * (lo + hi);
}

double chi2GateBound(double p, int dof)
{
	return p >= 1 ? std::numeric_limits<double>::infinity() : chi2Quantile(p, dof);
}

}  // namespace esif
