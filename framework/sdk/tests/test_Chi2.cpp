/// \file test_Chi2.cpp
/// The chi-square distribution behind every gate and consistency bound
/// (association/Chi2.h, Boost.Math): closed forms where they exist, the
/// quantiles the gates used before (esif's own series, correct to 1e-12
/// below a few hundred degrees of freedom), the round trip through the CDF
/// up to the whole-state dimensions of large maps, and bad arguments.

#include <esif/association/Chi2.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace
{
using esif::chi2Cdf;
using esif::chi2GateBound;
using esif::chi2Quantile;

double relative(double a, double b) { return std::abs(a - b) / std::abs(b); }

TEST(Chi2, ClosedFormsForOneAndTwoDegreesOfFreedom)
{
	// 2 dof: an exponential with mean 2, quantile -2 ln(1 - p).
	for (const double p : {0.05, 0.5, 0.95, 0.99, 0.9999})
		EXPECT_LT(relative(chi2Quantile(p, 2), -2.0 * std::log1p(-p)), 1e-13) << p;
	// 1 dof: the square of the normal quantile z_{(1+p)/2}.
	EXPECT_LT(relative(chi2Quantile(0.95, 1), 1.959963984540054 * 1.959963984540054), 1e-13);
	EXPECT_LT(relative(chi2Quantile(0.99, 1), 2.5758293035489004 * 2.5758293035489004), 1e-13);
}

TEST(Chi2, TheGatesKeepTheirQuantilesToOnePartIn1e12)
{
	// (p, dof, the quantile esif's series gave): the numbers every gate used.
	struct Row
	{
		double p;
		int dof;
		double before;
	};
	for (const Row& r : {Row{0.975, 3, 9.348403604499179}, Row{0.5, 7, 6.3458111955216712},
						 Row{0.99, 20, 37.566234786630261}, Row{0.9999, 60, 109.50293050036146},
						 Row{0.025, 300, 253.912322602448}})
		EXPECT_LT(relative(chi2Quantile(r.p, r.dof), r.before), 1e-12) << r.p << ", " << r.dof;
}

TEST(Chi2, QuantileAndCdfAreInversesUpToLargeStates)
{
	// Whole-state tests of large maps reach thousands of degrees of freedom,
	// where the former series underflowed (its quantile was 1490 at 3000
	// dof whatever p).
	for (const int dof : {1, 2, 3, 10, 100, 1000, 3000, 60000})
		for (const double p : {0.025, 0.5, 0.975})
		{
			const double x = chi2Quantile(p, dof);
			EXPECT_NEAR(chi2Cdf(x, dof), p, 1e-12) << dof << ", " << p;
		}
	EXPECT_NEAR(chi2Quantile(0.5, 3000) / 3000.0, 1.0, 1e-3);  // the median is about dof - 2/3
	EXPECT_EQ(chi2Cdf(-1.0, 4), 0.0);
	EXPECT_EQ(chi2Cdf(0.0, 4), 0.0);
}

TEST(Chi2, BadArgumentsThrowAndAGateAtOneIsOff)
{
	EXPECT_THROW(chi2Quantile(0.95, 0), std::invalid_argument);
	EXPECT_THROW(chi2Cdf(1.0, -2), std::invalid_argument);
	EXPECT_THROW(chi2Quantile(0.0, 2), std::invalid_argument);
	EXPECT_THROW(chi2Quantile(1.0, 2), std::invalid_argument);
	EXPECT_THROW(chi2Quantile(std::nan(""), 2), std::invalid_argument);
	EXPECT_EQ(chi2GateBound(1.0, 2), std::numeric_limits<double>::infinity());
	EXPECT_DOUBLE_EQ(chi2GateBound(0.95, 2), chi2Quantile(0.95, 2));
}

}  // namespace
