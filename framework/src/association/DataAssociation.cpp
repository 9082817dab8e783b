#include <esif/association/DataAssociation.h>
#include <esif/models/Se2.h>

#include <mrpt/math/CMatrixDynamic.h>
#include <mrpt/slam/data_association.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace esif
{
namespace
{
/// MRPT computes innovations as plain differences. Rotating every bearing so
/// the (-pi, pi] cut falls in the middle of the widest empty sector keeps
/// measured and predicted bearings of the same feature on the same side.
double bearingOffsetAwayFromCut(const AssociationInput& in)
{
	std::vector<double> angles;
	for (Eigen::Index i = 0; i < in.observations.rows(); ++i) angles.push_back(in.observations(i, 1));
	for (Eigen::Index j = 0; j < in.predictions.rows(); ++j) angles.push_back(in.predictions(j, 1));
	std::sort(angles.begin(), angles.end());
	double best_gap = angles.front() + 2 * M_PI - angles.back(), cut = angles.back() + 0.5 * best_gap;
	for (std::size_t k = 1; k < angles.size(); ++k)
	{
		const double gap = angles[k] - angles[k - 1];
		if (gap > best_gap)
		{
			best_gap = gap;
			cut = angles[k - 1] + 0.5 * gap;
		}
	}
	// Shift so that `cut` maps to pi.
	return M_PI - cut;
}

mrpt::math::CMatrixDouble toMrpt(const Eigen::MatrixXd& m)
{
	mrpt::math::CMatrixDouble out(m.rows(), m.cols());
	out.asEigen() = m;
	return out;
}

std::vector<double> minimumDistances(const Eigen::MatrixXd& z, const Eigen::MatrixXd& y, const Eigen::MatrixXd& S)
{
	std::vector<double> out(z.rows(), std::numeric_limits<double>::infinity());
	for (Eigen::Index j = 0; j < y.rows(); ++j)
	{
		const Eigen::LLT<Eigen::Matrix2d> llt(S.block<2, 2>(2 * j, 2 * j));
		if (llt.info() != Eigen::Success) continue;
		for (Eigen::Index i = 0; i < z.rows(); ++i)
		{
			const Eigen::Vector2d nu = (z.row(i) - y.row(j)).transpose();
			out[i] = std::min(out[i], nu.dot(llt.solve(nu)));
		}
	}
	return out;
}
}  // namespace

AssociationResult associate(const AssociationInput& input, AssociationMethod method, double gate_quantile)
{
	AssociationResult out;
	const auto M = input.observations.rows(), N = input.predictions.rows();
	out.candidate_of.assign(M, -1);
	out.min_distance2.assign(M, std::numeric_limits<double>::infinity());
	if (M == 0 || N == 0) return out;  // MRPT asserts both are non-empty

	const double offset = bearingOffsetAwayFromCut(input);
	Eigen::MatrixXd z = input.observations, y = input.predictions;
	for (Eigen::Index i = 0; i < M; ++i) z(i, 1) = wrapAngle(z(i, 1) + offset);
	for (Eigen::Index j = 0; j < N; ++j) y(j, 1) = wrapAngle(y(j, 1) + offset);

	mrpt::slam::TDataAssociationResults results;
	mrpt::slam::data_association_full_covariance(
		toMrpt(z), toMrpt(y), toMrpt(input.covariance), results,
		method == AssociationMethod::Jcbb ? mrpt::slam::assocJCBB : mrpt::slam::assocNN, mrpt::slam::metricMaha,
		gate_quantile, /*use_kdtree=*/false);

	for (const auto& [obs, pred] : results.associations)
		if (obs < static_cast<std::size_t>(M)) out.candidate_of[obs] = static_cast<int>(pred);
	out.min_distance2 = minimumDistances(z, y, input.covariance);
	out.jcbb_nodes = results.nNodesExploredInJCBB;
	return out;
}

}  // namespace esif
