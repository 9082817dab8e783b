#include "UpperLevelAssociation.h"

#include "PairFrame.h"
#include "ReferenceChoice.h"

#include <esif/localmap/MapLevelDecisions.h>
#include <esif/association/Chi2.h>
#include <esif/association/PointSetAssociation.h>
#include <esif/models/LocalMapObservation.h>
#include <esif/models/Se2.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace esif::lmj
{
namespace
{
double largestSigma(const Eigen::Matrix2d& cov)
{
	const double l = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov, Eigen::EigenvaluesOnly).eigenvalues()(1);
	return std::sqrt(std::max(0.0, l));
}

/// The points `moved` of a stacked list `xy` (joint covariance `cov`) in the
/// frame of its points a and b, with the covariance carried through
/// (first order): rows of the result follow `moved`.
void intoPairFrame(const Eigen::VectorXd& xy, const Eigen::MatrixXd& cov, int a, int b, const std::vector<int>& moved,
				   Eigen::MatrixXd& points, Eigen::MatrixXd& points_cov)
{
	const PairFrame f = pairFrame(xy.segment<2>(2 * a), xy.segment<2>(2 * b));
	const auto m = static_cast<Eigen::Index>(moved.size());
	Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * m, xy.size());
	points.resize(m, 2);
	for (Eigen::Index r = 0; r < m; ++r)
	{
		const PointInFrame p = pointInFrame(f.pose, xy.segment<2>(2 * moved[r]));
		points.row(r) = p.value.transpose();
		const Eigen::Matrix<double, 2, 4> d_pair = p.d_frame * f.d_pair;
		J.block<2, 2>(2 * r, 2 * moved[r]) = p.d_point;
		J.block<2, 2>(2 * r, 2 * a) += d_pair.leftCols<2>();
		J.block<2, 2>(2 * r, 2 * b) += d_pair.rightCols<2>();
	}
	points_cov = J * cov * J.transpose();
}

/// Global features within the local map's reach of f1 (Sec. 4.4.2 region
/// pruning), other than the known ones.
std::vector<LandmarkId> regionCandidates(
	const LocalMap& map, int f1, LandmarkId g1, double delta_m, const std::set<LandmarkId>& known,
	const relative::FeatureMap& global)
{
	double reach = 0;
	for (const auto& f : map.features) reach = std::max(reach, (f.position - map.features[f1].position).norm());
	const Eigen::Vector2d centre = global.position(g1);
	std::vector<LandmarkId> out;
	for (const LandmarkId id : global.ids())
		if (!known.count(id) && global.supported(id) && (global.position(id) - centre).norm() < reach + delta_m)
			out.push_back(id);
	return out;
}
/// Supported global features within reach of a local feature placed by
/// `start`: region_sigmas of the placement's position and heading
/// uncertainty (the heading's grows with the feature's distance from the
/// start) and of the feature's own, plus region_margin_m.
std::vector<LandmarkId> startFrameCandidates(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, const PoseEstimate& start,
	const relative::FeatureMap& global, const DslamLmjParams& params)
{
	const double sigma_xy = largestSigma(start.cov.topLeftCorner<2, 2>());
	const double sigma_phi = std::sqrt(std::max(0.0, start.cov(2, 2)));
	std::vector<Eigen::Vector2d> placed;
	std::vector<double> reach;
	for (std::size_t i = 0; i < map.features.size(); ++i)
	{
		const Eigen::Vector2d& p = map.features[i].position;
		const auto r = static_cast<Eigen::Index>(2 * i);
		placed.push_back(transformPoint(start.mean, p));
		reach.push_back(params.region_margin_m +
						params.region_sigmas * (sigma_xy + p.norm() * sigma_phi + largestSigma(local_cov.block<2, 2>(r, r))));
	}
	std::vector<LandmarkId> out;
	for (const LandmarkId id : global.ids())
	{
		if (!global.supported(id)) continue;
		const Eigen::Vector2d x = global.position(id);
		for (std::size_t i = 0; i < placed.size(); ++i)
			if ((placed[i] - x).norm() < reach[i])
			{
				out.push_back(id);
				break;
			}
	}
	return out;
}

/// Squared Mahalanobis distance of each local feature `others` from the
/// global feature of the same ID, both sides in the frame of the pair (a, b).
std::vector<double> pairFrameDistances2(const LocalMap& map, const Eigen::MatrixXd& local_cov, int a, int b,
										const std::vector<int>& others, relative::FeatureMap& global)
{
	Eigen::VectorXd local_xy(2 * map.features.size());
	for (std::size_t i = 0; i < map.features.size(); ++i) local_xy.segment<2>(2 * i) = map.features[i].position;
	Eigen::MatrixXd local, local_c, global_p, global_c;
	intoPairFrame(local_xy, local_cov, a, b, others, local, local_c);
	std::vector<LandmarkId> ids = {map.features[a].id, map.features[b].id};
	std::vector<int> moved;
	for (const int i : others) moved.push_back(static_cast<int>(ids.size())), ids.push_back(map.features[i].id);
	Eigen::VectorXd global_xy(2 * ids.size());
	for (std::size_t k = 0; k < ids.size(); ++k) global_xy.segment<2>(2 * k) = global.position(ids[k]);
	intoPairFrame(global_xy, global.covariance(ids), 0, 1, moved, global_p, global_c);
	std::vector<double> d2;
	for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(others.size()); ++k)
	{
		const Eigen::Matrix2d S = local_c.block<2, 2>(2 * k, 2 * k) + global_c.block<2, 2>(2 * k, 2 * k);
		const Eigen::Vector2d nu = (local.row(k) - global_p.row(k)).transpose();
		const Eigen::LLT<Eigen::Matrix2d> llt(S);
		d2.push_back(llt.info() == Eigen::Success ? nu.dot(llt.solve(nu)) : std::numeric_limits<double>::infinity());
	}
	return d2;
}

/// Squared Mahalanobis distance between the pair's baseline lengths in the
/// local and the global map (1 dof): what a pair frame cannot see, since it
/// fixes an origin and a direction but not a scale.
double baselineDistance2(const LocalMap& map, const Eigen::MatrixXd& local_cov, int a, int b,
						 relative::FeatureMap& global)
{
	const auto lengthAndVariance = [](const Eigen::Vector2d& pa, const Eigen::Vector2d& pb, const Eigen::Matrix4d& cov) {
		const Eigen::Vector2d d = pb - pa;
		const double length = d.norm();
		Eigen::Vector4d J;
		J << -d / length, d / length;
		return std::make_pair(length, J.dot(cov * J));
	};
	Eigen::Matrix4d Pl;
	Pl << local_cov.block<2, 2>(2 * a, 2 * a), local_cov.block<2, 2>(2 * a, 2 * b), local_cov.block<2, 2>(2 * b, 2 * a),
		local_cov.block<2, 2>(2 * b, 2 * b);
	const LandmarkId ga = map.features[a].id, gb = map.features[b].id;
	const auto [ll, vl] = lengthAndVariance(map.features[a].position, map.features[b].position, Pl);
	const auto [lg, vg] = lengthAndVariance(global.position(ga), global.position(gb), global.covariance({ga, gb}));
	return (ll - lg) * (ll - lg) / (vl + vg);
}

/// The ID-matched features of `eligible` that fail the gate in the frame of
/// the reference pair chosen among them without `excluded` (all of
/// `eligible` when the pair's own baseline fails); nullopt when no pair can
/// be chosen.
std::optional<std::vector<int>> failingInPairFrame(const LocalMap& map, const Eigen::MatrixXd& local_cov,
												   const std::vector<int>& eligible, int excluded,
												   relative::FeatureMap& global, const DslamLmjParams& params,
												   std::pair<int, int>& pair_used)
{
	const double gate = params.idGateDistance2();
	std::vector<Eigen::Vector2d> points;
	for (const auto& f : map.features) points.push_back(f.position);
	std::vector<int> usable;
	for (const int i : eligible)
		if (i != excluded) usable.push_back(i);
	const auto pair =
		chooseReferenceFeatures(points, usable, params.reference_min_separation_m, params.reference_min_clearance_m);
	if (!pair) return std::nullopt;
	pair_used = *pair;
	if (!(baselineDistance2(map, local_cov, pair->first, pair->second, global) <=
		  chi2Quantile(params.id_gate_chi2_quantile, 1)))
		return eligible;
	std::vector<int> others;
	for (const int i : eligible)
		if (i != pair->first && i != pair->second) others.push_back(i);
	const auto d2 = pairFrameDistances2(map, local_cov, pair->first, pair->second, others, global);
	std::vector<int> failing;
	for (std::size_t k = 0; k < others.size(); ++k)
		if (!(d2[k] <= gate)) failing.push_back(others[k]);
	return failing;
}
/// Of the `eligible` local features (each named by the ID of its global
/// feature), those that fail the id gate in the frame of a reference pair
/// chosen among them; when more than half fail, a member of the pair is
/// suspect and the pair is chosen again without it (first without f1, then
/// without f2), keeping the attempt with the fewest failures. Nothing is
/// tested with fewer than three.
std::vector<int> failingPairGate(const LocalMap& map, const Eigen::MatrixXd& local_cov, const std::vector<int>& eligible,
								 relative::FeatureMap& global, const DslamLmjParams& params)
{
	const double gate = params.idGateDistance2();
	if (eligible.size() < 3 || std::isinf(gate)) return {};
	std::pair<int, int> pair{-1, -1};
	auto failing = failingInPairFrame(map, local_cov, eligible, -1, global, params, pair);
	if (!failing) return {};
	const std::size_t tested = eligible.size() - 2;
	if (2 * failing->size() > tested)
		for (const int excluded : {pair.first, pair.second})
		{
			std::pair<int, int> other_pair;
			const auto retry = failingInPairFrame(map, local_cov, eligible, excluded, global, params, other_pair);
			if (retry && retry->size() < failing->size()) failing = retry;
		}
	return *failing;
}
/// The local features `points` (their own joint covariance) and the
/// `candidates` moved into the local map's frame by `start`, with the
/// first-order covariance of [start; candidates] (the two independent).
PointSets inStartFrame(const LocalMap& map, const Eigen::MatrixXd& local_cov, const std::vector<int>& points,
					   const PoseEstimate& start, const std::vector<LandmarkId>& candidates, relative::FeatureMap& global)
{
	PointSets sets;
	const auto M = static_cast<Eigen::Index>(points.size());
	std::vector<Eigen::Index> rows;
	sets.observed.resize(M, 2);
	for (Eigen::Index u = 0; u < M; ++u)
	{
		sets.observed.row(u) = map.features[points[u]].position.transpose();
		rows.push_back(2 * points[u]);
		rows.push_back(2 * points[u] + 1);
	}
	sets.observed_cov = local_cov(rows, rows);
	const auto N = static_cast<Eigen::Index>(candidates.size());
	Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * N, 3 + 2 * N);
	sets.candidates.resize(N, 2);
	for (Eigen::Index c = 0; c < N; ++c)
	{
		const PointInFrame y = pointInFrame(start.mean, global.position(candidates[c]));
		sets.candidates.row(c) = y.value.transpose();
		J.block<2, 3>(2 * c, 0) = y.d_frame;
		J.block<2, 2>(2 * c, 3 + 2 * c) = y.d_point;
	}
	Eigen::MatrixXd P = Eigen::MatrixXd::Zero(3 + 2 * N, 3 + 2 * N);
	P.topLeftCorner<3, 3>() = start.cov;
	P.bottomRightCorner(2 * N, 2 * N) = global.covariance(candidates);
	sets.candidates_cov = J * P * J.transpose();
	return sets;
}
}  // namespace

std::vector<std::optional<LandmarkId>> knownGlobalIds(
	const LocalMap& map, bool use_ids, const std::map<LandmarkId, LandmarkId>& global_of_local,
	const relative::FeatureMap& global)
{
	std::vector<std::optional<LandmarkId>> out;
	std::map<LandmarkId, int> claims;
	for (const auto& f : map.features)
	{
		if (use_ids)
			out.push_back(global.contains(f.id) ? std::optional<LandmarkId>(f.id) : std::nullopt);
		else if (const auto it = global_of_local.find(f.id); it != global_of_local.end() && global.contains(it->second))
			out.push_back(it->second);
		else
			out.push_back(std::nullopt);
		if (out.back()) ++claims[*out.back()];
	}
	// Two local features that earlier fusions gave one global feature (an
	// earlier association merged them) cannot both be it: neither is known,
	// and the association decides between them.
	for (auto& known : out)
		if (known && claims[*known] > 1) known.reset();
	return out;
}

UpperLevelOutcome associateByIds(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, relative::FeatureMap& global, const DslamLmjParams& params)
{
	UpperLevelOutcome out;
	std::vector<int> eligible;
	for (std::size_t i = 0; i < map.features.size(); ++i)
	{
		const LandmarkId id = map.features[i].id;
		out.decisions.associations.push_back(
			{global.contains(id) ? Association::Kind::Matched : Association::Kind::New, id});
		if (global.contains(id) && global.supported(id)) eligible.push_back(static_cast<int>(i));
	}
	const std::vector<int> failing = failingPairGate(map, local_cov, eligible, global, params);
	for (const int i : failing) out.decisions.associations[i].kind = Association::Kind::Rejected;
	out.tally.id_gate_rejected = failing.size();
	return out;
}

std::optional<UpperLevelOutcome> associateInPairFrame(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, const std::vector<std::optional<LandmarkId>>& known,
	relative::FeatureMap& global, const DslamLmjParams& params)
{
	std::vector<Eigen::Vector2d> points;
	std::vector<int> pair_eligible, unknown_indices;
	std::set<LandmarkId> known_ids;
	for (std::size_t i = 0; i < map.features.size(); ++i)
	{
		points.push_back(map.features[i].position);
		if (!known[i])
			unknown_indices.push_back(static_cast<int>(i));
		else if (global.supported(*known[i]))  // not one whose only information was withdrawn
			pair_eligible.push_back(static_cast<int>(i));
		if (known[i]) known_ids.insert(*known[i]);
	}
	const auto pair = chooseReferenceFeatures(
		points, pair_eligible, params.reference_min_separation_m, params.reference_min_clearance_m);
	if (!pair) return std::nullopt;
	const auto [a, b] = *pair;
	const LandmarkId g1 = *known[a], g2 = *known[b];

	UpperLevelOutcome out;
	for (std::size_t i = 0; i < map.features.size(); ++i)
		out.decisions.associations.push_back(
			known[i] ? Association{Association::Kind::Matched, *known[i]}
					 : Association{Association::Kind::New, map.features[i].id});
	if (unknown_indices.empty()) return out;

	const double delta_m = params.region_sigmas * largestSigma(global.covariance({g1})) + params.region_margin_m;
	const std::vector<LandmarkId> candidates = regionCandidates(map, a, g1, delta_m, known_ids, global);
	out.tally.candidates = candidates.size();
	if (candidates.empty()) return out;

	// Both sides in the frame of the pair: the local features from the local
	// map alone, the candidates from the global map alone.
	PointSets sets;
	Eigen::VectorXd local_xy(2 * points.size());
	for (std::size_t i = 0; i < points.size(); ++i) local_xy.segment<2>(2 * i) = points[i];
	intoPairFrame(local_xy, local_cov, a, b, unknown_indices, sets.observed, sets.observed_cov);
	std::vector<LandmarkId> global_ids = {g1, g2};
	global_ids.insert(global_ids.end(), candidates.begin(), candidates.end());
	Eigen::VectorXd global_xy(2 * global_ids.size());
	for (std::size_t i = 0; i < global_ids.size(); ++i) global_xy.segment<2>(2 * i) = global.position(global_ids[i]);
	std::vector<int> moved(candidates.size());
	for (std::size_t c = 0; c < candidates.size(); ++c) moved[c] = static_cast<int>(c + 2);
	intoPairFrame(global_xy, global.covariance(global_ids), 0, 1, moved, sets.candidates, sets.candidates_cov);

	applyMapLevelDecisions(decideMapFeatures(sets, params), unknown_indices, candidates, out.decisions, out.tally);
	return out;
}

UpperLevelOutcome associateInStartFrame(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, const std::vector<std::optional<LandmarkId>>& known,
	const PoseEstimate& start, relative::FeatureMap& global, const DslamLmjParams& params)
{
	UpperLevelOutcome out;
	std::vector<int> unknown;
	std::set<LandmarkId> known_ids;
	for (std::size_t i = 0; i < map.features.size(); ++i)
	{
		out.decisions.associations.push_back(known[i] ? Association{Association::Kind::Matched, *known[i]}
													  : Association{Association::Kind::New, map.features[i].id});
		if (known[i])
			known_ids.insert(*known[i]);
		else
			unknown.push_back(static_cast<int>(i));
	}
	std::vector<LandmarkId> candidates;
	for (const LandmarkId id : startFrameCandidates(map, local_cov, start, global, params))
		if (!known_ids.count(id)) candidates.push_back(id);
	out.tally.candidates = candidates.size();
	if (!candidates.empty() && !unknown.empty())
	{
		// The features matched by ID join the joint test as anchors, their
		// global features after the other candidates.
		const int first_anchor_candidate = static_cast<int>(candidates.size());
		std::vector<int> points = unknown;
		for (std::size_t i = 0; i < map.features.size(); ++i)
			if (known[i]) points.push_back(static_cast<int>(i)), candidates.push_back(*known[i]);
		applyMapLevelDecisions(
			decideMapFeaturesGivenAnchors(inStartFrame(map, local_cov, points, start, candidates, global),
										  unknown.size(), first_anchor_candidate, params),
			unknown, candidates, out.decisions, out.tally);
	}
	rejectMatchesFailingPairGate(map, local_cov, global, params, out);
	return out;
}

std::size_t ownFeaturesPlacedInGlobalMap(const LandmarkEkf& open_map, const std::set<LandmarkId>& own_ids,
										 const PoseEstimate& frame, const relative::FeatureMap& global,
										 double gate_quantile)
{
	const double gate = chi2GateBound(gate_quantile, 2);
	const auto P = open_map.core().covariance();
	std::size_t count = 0;
	for (std::size_t i = 0; i < open_map.ids().size(); ++i)
	{
		if (!own_ids.count(open_map.ids()[i])) continue;
		const auto r = static_cast<Eigen::Index>(3 + 2 * i);
		const PointFromFrame placed = pointFromFrame(frame.mean, open_map.core().landmark(i));
		const Eigen::Matrix2d S = placed.d_frame * frame.cov * placed.d_frame.transpose() +
			placed.d_point * P.block<2, 2>(r, r) * placed.d_point.transpose();
		const Eigen::LLT<Eigen::Matrix2d> llt(S);
		if (llt.info() != Eigen::Success) continue;
		const auto passes = [&](LandmarkId id) {
			if (!global.supported(id)) return false;
			const Eigen::Vector2d nu = placed.value - global.position(id);
			return nu.dot(llt.solve(nu)) <= gate;
		};
		count += std::any_of(global.ids().begin(), global.ids().end(), passes);
	}
	return count;
}

void rejectMatchesFailingPairGate(const LocalMap& map, const Eigen::MatrixXd& local_cov, relative::FeatureMap& global,
								  const DslamLmjParams& params, UpperLevelOutcome& outcome)
{
	LocalMap named;	 // the features only, each named by the global feature it was matched to
	named.features = map.features;
	std::vector<int> eligible;
	for (std::size_t i = 0; i < map.features.size(); ++i)
	{
		const Association& a = outcome.decisions.associations[i];
		if (a.kind != Association::Kind::Matched || !global.supported(a.id)) continue;
		named.features[i].id = a.id;
		eligible.push_back(static_cast<int>(i));
	}
	const std::vector<int> failing = failingPairGate(named, local_cov, eligible, global, params);
	for (const int i : failing) outcome.decisions.associations[i] = {Association::Kind::Rejected, -1};
	outcome.tally.pairs_dropped += failing.size();
}

}  // namespace esif::lmj
