#pragma once
/// \file MarginalCovariances.h
/// Marginal covariances of chosen parameter blocks at the optimum: the
/// diagonal blocks of (J^T J)^-1, computed by ceres::Covariance from a sparse
/// QR factorization of J (SuiteSparseQR), never by inverting J^T J.

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <unordered_map>
#include <vector>

namespace esif::ceres_full
{
/// Covariance of every block in `blocks` (each its own diagonal block).
/// Throws NumericalError when J is rank deficient (an unobservable block) or
/// cannot be evaluated (a non-finite derivative).
std::unordered_map<const double*, Eigen::MatrixXd> marginalCovariances(
	ceres::Problem& problem, const std::vector<const double*>& blocks, int threads);

}  // namespace esif::ceres_full
