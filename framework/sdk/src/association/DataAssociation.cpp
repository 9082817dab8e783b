#include "Jcbb.h"
#include "MrptMatrix.h"

#include <esif/association/Chi2.h>
#include <esif/association/DataAssociation.h>
#include <esif/models/Se2.h>

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

struct ShiftedBearings
{
	Eigen::MatrixXd z, y;  ///< observations, predictions
};

/// The input's observations and predictions with every bearing rotated by
/// bearingOffsetAwayFromCut.
ShiftedBearings shiftedAwayFromCut(const AssociationInput& in)
{
	const double offset = bearingOffsetAwayFromCut(in);
	ShiftedBearings b{in.observations, in.predictions};
	for (Eigen::Index i = 0; i < b.z.rows(); ++i) b.z(i, 1) = wrapAngle(b.z(i, 1) + offset);
	for (Eigen::Index j = 0; j < b.y.rows(); ++j) b.y(j, 1) = wrapAngle(b.y(j, 1) + offset);
	return b;
}

/// Squared Mahalanobis distance of every (observation, prediction) pair, with
/// the prediction's diagonal block as covariance (as MRPT computes it);
/// infinity where that block is not positive definite.
Eigen::MatrixXd pairDistances(const Eigen::MatrixXd& z, const Eigen::MatrixXd& y, const Eigen::MatrixXd& S)
{
	Eigen::MatrixXd d2 = Eigen::MatrixXd::Constant(z.rows(), y.rows(), std::numeric_limits<double>::infinity());
	for (Eigen::Index j = 0; j < y.rows(); ++j)
	{
		const Eigen::LLT<Eigen::Matrix2d> llt(S.block<2, 2>(2 * j, 2 * j));
		if (llt.info() != Eigen::Success) continue;
		for (Eigen::Index i = 0; i < z.rows(); ++i)
		{
			const Eigen::Vector2d nu = (z.row(i) - y.row(j)).transpose();
			d2(i, j) = nu.dot(llt.solve(nu));
		}
	}
	return d2;
}

/// The fallback's joint compatibility test (Neira & Tardos 2001): while the
/// pairs fail it, the pair that contributes most to the joint distance is
/// dropped (jcbb::dropUntilJointlyCompatible; the one with the largest
/// individual distance when the joint covariance is not positive definite).
std::size_t enforceJointCompatibility(const Eigen::MatrixXd& z, const Eigen::MatrixXd& y, const Eigen::MatrixXd& S,
									  const Eigen::MatrixXd& d2, double quantile, std::vector<int>& candidate_of)
{
	const auto stack = [&](const std::vector<int>& pairs) { return jcbb::jointInnovation(z, y, S, pairs); };
	const auto farthest = [&](const jcbb::JointInnovation& joint)
	{
		Eigen::Index worst = joint.observations.front();
		for (const Eigen::Index i : joint.observations)
			if (d2(i, candidate_of[i]) > d2(worst, candidate_of[worst])) worst = i;
		return worst;
	};
	double distance2 = 0;
	return jcbb::dropUntilJointlyCompatible(candidate_of, quantile, stack, farthest, distance2);
}

/// Individually compatible candidates of each observation (what the search branches on).
std::vector<int> compatibleCounts(const Eigen::MatrixXd& d2, double gate_quantile)
{
	const double threshold = chi2Quantile(gate_quantile, 2);
	std::vector<int> counts(d2.rows(), 0);
	for (Eigen::Index i = 0; i < d2.rows(); ++i) counts[i] = static_cast<int>((d2.row(i).array() < threshold).count());
	return counts;
}
}  // namespace

Eigen::MatrixXd individualDistances2(const AssociationInput& input)
{
	if (input.observations.rows() == 0 || input.predictions.rows() == 0)
		return Eigen::MatrixXd(input.observations.rows(), input.predictions.rows());
	const ShiftedBearings b = shiftedAwayFromCut(input);
	return pairDistances(b.z, b.y, input.covariance);
}

AssociationResult associate(
	const AssociationInput& input, AssociationMethod method, double gate_quantile, const SearchBounds& bounds)
{
	AssociationResult out;
	const auto M = input.observations.rows(), N = input.predictions.rows();
	out.candidate_of.assign(M, -1);
	out.min_distance2.assign(M, std::numeric_limits<double>::infinity());
	if (M == 0 || N == 0) return out;  // MRPT asserts both are non-empty

	const auto [z, y] = shiftedAwayFromCut(input);
	const Eigen::MatrixXd d2 = pairDistances(z, y, input.covariance);
	for (Eigen::Index i = 0; i < M; ++i) out.min_distance2[i] = d2.row(i).minCoeff();

	out.effort = searchEffort(compatibleCounts(d2, gate_quantile));
	out.fell_back = method == AssociationMethod::Jcbb && !out.effort.within(bounds);
	const bool jcbb = method == AssociationMethod::Jcbb && !out.fell_back;

	if (jcbb)
	{
		const jcbb::Hypothesis h = jcbb::search({z, y, input.covariance, d2, gate_quantile});
		out.candidate_of = h.candidate_of;
		out.jcbb_nodes = h.nodes;
	}
	else
	{
		mrpt::slam::TDataAssociationResults results;
		mrpt::slam::data_association_full_covariance(
			toMrpt(z), toMrpt(y), toMrpt(input.covariance), results, mrpt::slam::assocNN, mrpt::slam::metricMaha,
			gate_quantile, /*use_kdtree=*/false);
		for (const auto& [obs, pred] : results.associations)
			if (obs < static_cast<std::size_t>(M)) out.candidate_of[obs] = static_cast<int>(pred);
	}
	if (out.fell_back)
		out.pairs_dropped = enforceJointCompatibility(z, y, input.covariance, d2, gate_quantile, out.candidate_of);
	return out;
}

}  // namespace esif
