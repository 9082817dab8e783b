#include "MarginalCovariances.h"

#include "QuietCeresLogging.h"

#include <esif/core/Errors.h>

namespace esif::ceres_full
{
std::unordered_map<const double*, Eigen::MatrixXd> marginalCovariances(
	ceres::Problem& problem, const std::vector<const double*>& blocks, int threads)
{
	ceres::Covariance::Options options;
	options.algorithm_type = ceres::SPARSE_QR;
	options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
	options.num_threads = threads;
	ceres::Covariance covariance(options);

	std::vector<std::pair<const double*, const double*>> pairs;
	pairs.reserve(blocks.size());
	const QuietCeresLogging quiet;  // the caller tells of a failure
	for (const double* b : blocks) pairs.emplace_back(b, b);
	if (!covariance.Compute(pairs, &problem))
		throw NumericalError(
			"marginal covariances: the Jacobian is rank deficient or not finite (a pose or landmark is unobservable, "
			"or a pose sits on a landmark)");

	std::unordered_map<const double*, Eigen::MatrixXd> out;
	for (const double* b : blocks)
	{
		const int n = problem.ParameterBlockSize(b);
		Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> cov(n, n);
		covariance.GetCovarianceBlock(b, b, cov.data());
		const Eigen::MatrixXd symmetric = 0.5 * (cov + cov.transpose());
		out.emplace(b, symmetric);
	}
	return out;
}

}  // namespace esif::ceres_full
