#include <esif/association/Ambiguity.h>
#include <esif/association/Chi2.h>
#include <esif/association/PointSetAssociation.h>
#include "Jcbb.h"
#include "MrptMatrix.h"

#include <mrpt/slam/data_association.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <limits>
#include <stdexcept>

namespace esif
{
namespace
{
void checkSizes(const PointSets& s)
{
	const auto M = s.observed.rows(), N = s.candidates.rows();
	if (s.observed.cols() != 2 || s.candidates.cols() != 2 || s.observed_cov.rows() != 2 * M ||
		s.observed_cov.cols() != 2 * M || s.candidates_cov.rows() != 2 * N || s.candidates_cov.cols() != 2 * N)
		throw std::invalid_argument("associatePointSets: point and covariance sizes do not match");
}

/// Exact squared Mahalanobis distance of pair (i, c); infinity when its
/// covariance is not positive definite.
double pairDistance2(const PointSets& s, Eigen::Index i, Eigen::Index c)
{
	const Eigen::Matrix2d S = s.observed_cov.block<2, 2>(2 * i, 2 * i) + s.candidates_cov.block<2, 2>(2 * c, 2 * c);
	const Eigen::LLT<Eigen::Matrix2d> llt(S);
	if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
	const Eigen::Vector2d nu = (s.observed.row(i) - s.candidates.row(c)).transpose();
	return nu.dot(llt.solve(nu));
}

/// The pairs (i, candidate_of[i] >= 0) stacked: innovations, joint
/// covariance (both sets' joint blocks), observed points and candidates.
using StackedPairs = jcbb::JointInnovation;
StackedPairs stackedPairs(const PointSets& s, const std::vector<int>& candidate_of)
{
	return jcbb::jointInnovation(s.observed, s.candidates, s.candidates_cov, candidate_of, &s.observed_cov);
}

/// Of the stacked pairs `p`, the observed point farthest from its
/// candidate on its own: the pair to drop when the joint covariance cannot
/// name one (not positive definite).
Eigen::Index farthestAlone(const PointSets& s, const StackedPairs& p)
{
	Eigen::Index worst = 0;
	double worst_d2 = -1;
	for (std::size_t a = 0; a < p.observations.size(); ++a)
		if (const double d2 = pairDistance2(s, p.observations[a], p.candidates[a]); d2 > worst_d2)
			worst_d2 = d2, worst = p.observations[a];
	return worst;
}

/// Point i against candidate c given the pairs `p` (point i not among
/// them), the pairs' shared placement error taken out: with nu_A, S_AA the
/// stacked pairs and C = Cov(nu_ic, nu_A), the pair (i, c) has innovation
/// nu_ic - C S_AA^-1 nu_A and covariance S_ic - C S_AA^-1 C^T. `w` is
/// S_AA^-1 nu_A; with no pairs the pair is returned as it stands.
struct ConditionalPair
{
	Eigen::Vector2d nu;
	Eigen::Matrix2d S;
};
ConditionalPair conditionalPair(const PointSets& s, const StackedPairs& p, const Eigen::LLT<Eigen::MatrixXd>& pairs,
								const Eigen::VectorXd& w, Eigen::Index i, Eigen::Index c)
{
	ConditionalPair out{(s.observed.row(i) - s.candidates.row(c)).transpose(),
						s.observed_cov.block<2, 2>(2 * i, 2 * i) + s.candidates_cov.block<2, 2>(2 * c, 2 * c)};
	const auto k = static_cast<Eigen::Index>(p.observations.size());
	if (k == 0) return out;
	Eigen::MatrixXd C(2, 2 * k);
	for (Eigen::Index a = 0; a < k; ++a)
		C.middleCols<2>(2 * a) =
			s.observed_cov.block<2, 2>(2 * i, 2 * p.observations[a]) + s.candidates_cov.block<2, 2>(2 * c, 2 * p.candidates[a]);
	out.nu -= C * w;
	out.S -= C * pairs.solve(C.transpose());
	return out;
}

/// Squared distances of point i to every candidate given the pairs `p`.
Eigen::VectorXd conditionalDistances2(const PointSets& s, const StackedPairs& p, const Eigen::LLT<Eigen::MatrixXd>& pairs,
									  const Eigen::VectorXd& w, Eigen::Index i)
{
	Eigen::VectorXd d2(s.candidates.rows());
	for (Eigen::Index c = 0; c < s.candidates.rows(); ++c)
	{
		const ConditionalPair pc = conditionalPair(s, p, pairs, w, i, c);
		const Eigen::LLT<Eigen::Matrix2d> llt(pc.S);
		d2(c) = llt.info() == Eigen::Success ? pc.nu.dot(llt.solve(pc.nu)) : std::numeric_limits<double>::infinity();
	}
	return d2;
}

/// For each observed point without a candidate, its smallest squared
/// distance to a candidate conditioned on the accepted pairs (conditionalPair).
std::vector<double> conditionalMinDistances2(const PointSets& s, const std::vector<int>& candidate_of,
											 const std::vector<double>& min_distance2)
{
	std::vector<double> out(candidate_of.size(), std::numeric_limits<double>::infinity());
	const StackedPairs p = stackedPairs(s, candidate_of);
	const Eigen::LLT<Eigen::MatrixXd> pairs(p.S);
	const bool conditioned = !p.observations.empty() && pairs.info() == Eigen::Success;
	const Eigen::VectorXd w = conditioned ? pairs.solve(p.nu) : Eigen::VectorXd();
	for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(candidate_of.size()); ++i)
	{
		if (candidate_of[i] >= 0) continue;
		if (!conditioned)
		{
			out[i] = min_distance2[i];
			continue;
		}
		out[i] = conditionalDistances2(s, p, pairs, w, i).minCoeff();
	}
	return out;
}

/// Each candidate's covariance for MRPT: its joint block plus the covariance
/// of its nearest observed point (Euclidean).
Eigen::MatrixXd mrptPredictionCovariance(const PointSets& s)
{
	Eigen::MatrixXd cov = s.candidates_cov;
	for (Eigen::Index c = 0; c < s.candidates.rows(); ++c)
	{
		Eigen::Index nearest = 0;
		(s.observed.rowwise() - s.candidates.row(c)).rowwise().squaredNorm().minCoeff(&nearest);
		cov.block<2, 2>(2 * c, 2 * c) += s.observed_cov.block<2, 2>(2 * nearest, 2 * nearest);
	}
	return 0.5 * (cov + cov.transpose());
}

/// Individual compatibility as MRPT's NN judges it: the innovation
/// of pair (i, c) against candidate c's block of the prediction covariance
/// handed to MRPT (which holds the observation noise, see above).
std::vector<int> mrptCompatibleCounts(const PointSets& s, const Eigen::MatrixXd& prediction_cov, double gate)
{
	std::vector<int> counts(static_cast<std::size_t>(s.observed.rows()), 0);
	for (Eigen::Index c = 0; c < s.candidates.rows(); ++c)
	{
		const Eigen::LLT<Eigen::Matrix2d> llt(prediction_cov.block<2, 2>(2 * c, 2 * c));
		if (llt.info() != Eigen::Success) continue;
		for (Eigen::Index i = 0; i < s.observed.rows(); ++i)
		{
			const Eigen::Vector2d nu = (s.observed.row(i) - s.candidates.row(c)).transpose();
			counts[static_cast<std::size_t>(i)] += nu.dot(llt.solve(nu)) <= gate;
		}
	}
	return counts;
}

/// MRPT's nearest-neighbour hypothesis; a candidate claimed twice goes to
/// the closer point. Only the observations `pairable` (those with a
/// compatible candidate) are handed to MRPT: the others can only stay unpaired.
std::vector<int> mrptNearestNeighbour(const PointSets& s, const Eigen::MatrixXd& prediction_cov,
									  const std::vector<Eigen::Index>& pairable, double gate_quantile)
{
	std::vector<int> candidate_of(s.observed.rows(), -1);
	if (pairable.empty()) return candidate_of;
	Eigen::MatrixXd observed(static_cast<Eigen::Index>(pairable.size()), 2);
	for (std::size_t k = 0; k < pairable.size(); ++k) observed.row(static_cast<Eigen::Index>(k)) = s.observed.row(pairable[k]);
	mrpt::slam::TDataAssociationResults results;
	mrpt::slam::data_association_full_covariance(
		toMrpt(observed), toMrpt(s.candidates), toMrpt(prediction_cov), results, mrpt::slam::assocNN,
		mrpt::slam::metricMaha, gate_quantile, /*use_kdtree=*/false);
	std::vector<int> owner(s.candidates.rows(), -1);
	for (const auto& [obs, pred] : results.associations)
	{
		if (obs >= pairable.size() || pred >= static_cast<std::size_t>(s.candidates.rows())) continue;
		const int i = static_cast<int>(pairable[obs]), c = static_cast<int>(pred);
		if (owner[c] >= 0)
		{
			if (pairDistance2(s, owner[c], c) <= pairDistance2(s, i, c)) continue;
			candidate_of[owner[c]] = -1;
		}
		owner[c] = i;
		candidate_of[i] = c;
	}
	return candidate_of;
}

/// MRPT's nearest neighbour pairs each observation on its own, in order, so
/// a farther point can keep a candidate a closer one is compatible with;
/// between clustered features (trees a metre apart) that is a wrong
/// association. Moves that
/// keep the number of pairs and lower the summed exact individual distance
/// are made until none is left: a pair takes a closer free candidate, a
/// candidate goes to a closer unmatched point, or two pairs swap candidates.
/// `d2`: the exact individual squared distances (M x N).
void improveByExchange(const Eigen::MatrixXd& d2, double gate, std::vector<int>& candidate_of)
{
	const auto M = d2.rows(), N = d2.cols();
	std::vector<int> owner(N, -1);
	for (Eigen::Index i = 0; i < M; ++i)
		if (candidate_of[i] >= 0) owner[candidate_of[i]] = static_cast<int>(i);
	auto assign = [&](int i, int c) {
		if (candidate_of[i] >= 0) owner[candidate_of[i]] = -1;
		candidate_of[i] = c;
		if (c >= 0) owner[c] = i;
	};
	for (bool moved = true; moved;)
	{
		moved = false;
		for (int i = 0; i < M; ++i)
			for (int c = 0; c < N; ++c)
			{
				const int cur = candidate_of[i], j = owner[c];
				if (c == cur || d2(i, c) > gate) continue;
				if (j < 0 && cur >= 0 && d2(i, c) < d2(i, cur))
					assign(i, c), moved = true;	 // a closer free candidate
				else if (j >= 0 && cur < 0 && d2(i, c) < d2(j, c))
					assign(j, -1), assign(i, c), moved = true;	// a closer unmatched point
				else if (j >= 0 && cur >= 0 && d2(j, cur) <= gate && d2(i, c) + d2(j, cur) < d2(i, cur) + d2(j, c))
					assign(j, -1), assign(i, c), assign(j, cur), moved = true;	// two pairs swap
			}
	}
}
}  // namespace

std::vector<bool> ambiguousPairs(const PointSets& s, const std::vector<int>& candidate_of, double margin_d2)
{
	// One factorisation of the other pairs per pair: O(pairs^4) in all,
	// meant for the tens of pairs of a local map associated without IDs.
	std::vector<bool> out(candidate_of.size(), false);
	if (margin_d2 <= 0) return out;
	for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(candidate_of.size()); ++i)
	{
		const int chosen = candidate_of[i];
		if (chosen < 0) continue;
		std::vector<int> others = candidate_of;
		others[i] = -1;
		const StackedPairs p = stackedPairs(s, others);
		const Eigen::LLT<Eigen::MatrixXd> pairs(p.S);
		if (!p.observations.empty() && pairs.info() != Eigen::Success) continue;
		const Eigen::VectorXd w = p.observations.empty() ? Eigen::VectorXd() : pairs.solve(p.nu);
		const Eigen::LLT<Eigen::Matrix2d> own(conditionalPair(s, p, pairs, w, i, chosen).S);
		if (own.info() != Eigen::Success) continue;
		out[i] = ambiguousMatch(conditionalDistances2(s, p, pairs, w, i), chosen, margin_d2, [&](Eigen::Index j) {
			const Eigen::Vector2d apart = (s.candidates.row(j) - s.candidates.row(chosen)).transpose();
			return apart.dot(own.solve(apart));
		});
	}
	return out;
}

PointAssociation associatePointSets(const PointSets& sets, AssociationMethod method, double gate_quantile,
									double joint_quantile, const SearchBounds& bounds)
{
	checkSizes(sets);
	PointAssociation out;
	const auto M = sets.observed.rows(), N = sets.candidates.rows();
	out.candidate_of.assign(M, -1);
	out.min_distance2.assign(M, std::numeric_limits<double>::infinity());
	out.conditional_min_distance2 = out.min_distance2;
	if (M == 0 || N == 0) return out;  // MRPT asserts both are non-empty

	const double individual_gate = chi2Quantile(gate_quantile, 2);
	Eigen::MatrixXd d2(M, N);
	std::vector<int> compatible(M, 0);
	for (Eigen::Index i = 0; i < M; ++i)
		for (Eigen::Index c = 0; c < N; ++c)
		{
			d2(i, c) = pairDistance2(sets, i, c);
			out.min_distance2[i] = std::min(out.min_distance2[i], d2(i, c));
			compatible[i] += d2(i, c) <= individual_gate;
		}
	// The search effort counts the exact compatible candidates, or those
	// MRPT's nearest neighbour (the fallback) sees where that is more (its
	// covariance is looser than the exact one for some pairs).
	const Eigen::MatrixXd prediction_cov = mrptPredictionCovariance(sets);
	const std::vector<int> mrpt_compatible = mrptCompatibleCounts(sets, prediction_cov, individual_gate);
	std::vector<Eigen::Index> pairable;
	for (Eigen::Index i = 0; i < M; ++i)
	{
		compatible[i] = std::max(compatible[i], mrpt_compatible[i]);
		if (mrpt_compatible[i] > 0) pairable.push_back(i);
	}
	out.effort = searchEffort(compatible);
	out.fell_back = method == AssociationMethod::Jcbb && !out.effort.within(bounds);

	if (method == AssociationMethod::Jcbb && !out.fell_back)
	{
		// esif's JCBB (Jcbb.h), the observed points' own covariance in every joint test.
		const jcbb::Hypothesis h =
			jcbb::search({sets.observed, sets.candidates, sets.candidates_cov, d2, gate_quantile, &sets.observed_cov});
		out.candidate_of = h.candidate_of;
		out.jcbb_nodes = h.nodes;
	}
	else
	{
		out.candidate_of = mrptNearestNeighbour(sets, prediction_cov, pairable, gate_quantile);
		improveByExchange(d2, individual_gate, out.candidate_of);
		// MRPT gated on its looser covariance: a pair beyond the exact
		// individual gate is dropped (JCBB only pairs within it).
		for (Eigen::Index i = 0; i < M; ++i)
			if (out.candidate_of[i] >= 0 && d2(i, out.candidate_of[i]) > individual_gate)
				out.candidate_of[i] = -1, ++out.pairs_dropped;
	}

	// Exact joint compatibility; repair by dropping the pair whose removal
	// lowers the joint distance most (jcbb::jointVerdict), not the one
	// farthest on its own.
	out.pairs_dropped += jcbb::dropUntilJointlyCompatible(
		out.candidate_of, joint_quantile, [&](const std::vector<int>& pairs) { return stackedPairs(sets, pairs); },
		[&](const StackedPairs& p) { return farthestAlone(sets, p); }, out.joint_distance2);
	out.conditional_min_distance2 = conditionalMinDistances2(sets, out.candidate_of, out.min_distance2);
	return out;
}

}  // namespace esif
