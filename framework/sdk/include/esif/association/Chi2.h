#pragma once
/// \file Chi2.h
/// The chi-square distribution for integer degrees of freedom, through
/// Boost.Math (as the Monte Carlo bounds use it). MRPT's chi2inv() is the
/// Wilson-Hilferty approximation (5.937 instead of 5.991 for the 95%
/// quantile at 2 dof), too coarse for gates and consistency bounds.

namespace esif
{
/// P(X <= x) for X ~ chi-square with `dof` degrees of freedom (dof >= 1).
double chi2Cdf(double x, int dof);

/// The `p` quantile (0 < p < 1) of the chi-square with `dof` degrees of freedom.
double chi2Quantile(double p, int dof);

/// The squared-distance bound of an outlier gate set by its confidence `p`
/// in (0, 1]: chi2Quantile(p, dof), or +infinity for p = 1 (the gate is off).
double chi2GateBound(double p, int dof);

}  // namespace esif
