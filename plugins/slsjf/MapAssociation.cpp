#include "MapAssociation.h"

#include <esif/association/Chi2.h>
#include <esif/association/PointSetAssociation.h>
#include <esif/localmap/MapLevelDecisions.h>
#include <esif/models/LocalMapObservation.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <set>

namespace esif::slsjf
{
namespace
{
double largestSigma(const Eigen::Matrix2d& cov)
{
	return std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov, Eigen::EigenvaluesOnly).eigenvalues()(1)));
}

/// Sec. 5.4.1.1: features of the fused maps that can overlap the new one
/// and lie, by the estimates, within `slack_m` of one of the new map's
/// features moved into the global frame (the authors' MaxDistance test,
/// with a slack from the start pose's uncertainty instead of a constant).
std::vector<VarId> overlapCandidates(
	const GlobalMap& global, const Pose2& start, const std::vector<Eigen::Vector2d>& local_features,
	const MapExtent& extent, double margin_m, double slack_m, std::size_t& maps_selected)
{
	const Eigen::Vector2d origin = start.head<2>();
	std::vector<Eigen::Vector2d> placed;
	for (const auto& p : local_features) placed.push_back(transformPoint(start, p));
	const auto nearSomeLocalFeature = [&](const Eigen::Vector2d& x) {
		return std::any_of(placed.begin(), placed.end(), [&](const Eigen::Vector2d& p) { return (p - x).norm() < slack_m; });
	};
	std::set<int> chosen;
	for (const auto& fused : global.fusedMaps())
	{
		const Eigen::Vector2d o = global.startEstimate(fused.start).head<2>();
		const double reach = fused.extent.radius_m + extent.radius_m + fused.extent.start_uncertainty_m +
			extent.start_uncertainty_m + margin_m;
		if ((o - origin).norm() >= reach) continue;
		++maps_selected;
		for (const VarId v : fused.features)
			if (!chosen.count(v.value) && nearSomeLocalFeature(global.point(v))) chosen.insert(v.value);
	}
	std::vector<VarId> out;
	for (const int v : chosen) out.push_back(VarId{v});
	return out;
}

/// nu^T S^-1 nu <= gate; false when S is not positive definite.
bool insideGate(const Eigen::Matrix2d& S, const Eigen::Vector2d& nu, double gate)
{
	const Eigen::LLT<Eigen::Matrix2d> llt(S);
	return llt.info() == Eigen::Success && nu.dot(llt.solve(nu)) <= gate;
}

/// The candidates in the new map's frame, with their covariance from the
/// joint covariance of [start pose; candidates] (start-pose correlation included).
void candidatesInLocalFrame(
	GlobalMap& global, VarId start, const std::vector<VarId>& candidates, PointSets& sets)
{
	std::vector<VarId> vars = {start};
	vars.insert(vars.end(), candidates.begin(), candidates.end());
	const Eigen::MatrixXd P = global.covariance(vars);
	const Pose2 s = global.pose(start);
	const auto N = static_cast<Eigen::Index>(candidates.size());
	Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * N, 3 + 2 * N);
	sets.candidates.resize(N, 2);
	for (Eigen::Index c = 0; c < N; ++c)
	{
		const PointInFrame y = pointInFrame(s, global.point(candidates[c]));
		sets.candidates.row(c) = y.value.transpose();
		J.block<2, 3>(2 * c, 0) = y.d_frame;
		J.block<2, 2>(2 * c, 3 + 2 * c) = y.d_point;
	}
	sets.candidates_cov = J * P * J.transpose();
}

/// A local feature (index in the map) and the global feature of its ID.
struct IdMatch
{
	Eigen::Index local;
	VarId global;
};

Eigen::Matrix2d localBlock(const Eigen::MatrixXd& local_cov, Eigen::Index i)
{
	return local_cov.block<2, 2>(3 + 2 * i, 3 + 2 * i);
}

/// The ID gate's first test. The innovation's covariance S is the local
/// feature's plus the global feature's (moved into the local frame), so
/// S >= the local one and a match inside the gate under its local
/// covariance alone is inside it under S: the same decision, up to rounding
/// at the gate's edge, without recovering a covariance from the global map,
/// which under a large map's top separators costs far more than the test.
/// Returns the matches this test cannot accept. It reads the estimates after
/// the start pose's link (refreshed first), as the covariance recovery of
/// the second test does.
std::vector<IdMatch> undecidedByLocalGate(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, VarId start, GlobalMap& global,
	const std::vector<IdMatch>& matches, double gate)
{
	global.core().refresh();
	const Pose2 s = global.pose(start);
	std::vector<IdMatch> undecided;
	for (const IdMatch& m : matches)
	{
		const Eigen::Vector2d nu = map.features[m.local].position - pointInFrame(s, global.point(m.global)).value;
		if (!insideGate(localBlock(local_cov, m.local), nu, gate)) undecided.push_back(m);
	}
	return undecided;
}

/// The ID gate's second test, under both maps' covariances (one recovery
/// of the joint covariance of the start pose and the global features):
/// the local features that fail it.
std::vector<Eigen::Index> failingJointGate(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, VarId start, GlobalMap& global,
	const std::vector<IdMatch>& undecided, double gate)
{
	std::vector<Eigen::Index> failing;
	if (undecided.empty()) return failing;
	std::vector<VarId> vars;
	for (const IdMatch& m : undecided) vars.push_back(m.global);
	PointSets sets;
	candidatesInLocalFrame(global, start, vars, sets);
	for (std::size_t u = 0; u < undecided.size(); ++u)
	{
		const Eigen::Index i = undecided[u].local, c = static_cast<Eigen::Index>(u);
		const Eigen::Vector2d nu = map.features[i].position - sets.candidates.row(c).transpose();
		if (!insideGate(localBlock(local_cov, i) + sets.candidates_cov.block<2, 2>(2 * c, 2 * c), nu, gate))
			failing.push_back(i);
	}
	return failing;
}
}  // namespace

double mapRadius(const LocalMap& map, const Eigen::MatrixXd& local_cov, double sigmas)
{
	double radius = map.end_pose.head<2>().norm() + sigmas * largestSigma(local_cov.topLeftCorner<2, 2>());
	for (std::size_t i = 0; i < map.features.size(); ++i)
	{
		const auto r = static_cast<Eigen::Index>(3 + 2 * i);
		radius = std::max(radius, map.features[i].position.norm() + sigmas * largestSigma(local_cov.block<2, 2>(r, r)));
	}
	return radius;
}

MapAssociationOutcome associateByIds(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, std::optional<VarId> start, GlobalMap& global,
	const SlsjfParams& params)
{
	MapAssociationOutcome out;
	std::vector<IdMatch> matches;
	for (std::size_t i = 0; i < map.features.size(); ++i)
	{
		const auto& f = map.features[i];
		const auto var = global.featureVar(f.id);
		out.decisions.associations.push_back({var ? Association::Kind::Matched : Association::Kind::New, f.id});
		if (var) matches.push_back({static_cast<Eigen::Index>(i), *var});
	}
	const double gate = params.idGateDistance2();
	if (!start || matches.empty() || std::isinf(gate)) return out;
	const std::vector<IdMatch> undecided = undecidedByLocalGate(map, local_cov, *start, global, matches, gate);
	for (const Eigen::Index i : failingJointGate(map, local_cov, *start, global, undecided, gate))
	{
		out.decisions.associations[i].kind = Association::Kind::Rejected;
		++out.tally.id_gate_rejected;
	}
	return out;
}

namespace
{
/// A local feature whose ID named its global feature (associateByIds):
/// decided already, and part of the joint test of the others.
struct Anchor
{
	Eigen::Index local;
	VarId global;
};

/// Sec. 5.4.1 for the local features `chosen` (indices into the map): their
/// decisions in `out` become Matched, Rejected or stay New, given the
/// `anchors` (ID-matched features) and their global features
/// (decideMapFeaturesGivenAnchors).
void decideGeometrically(const LocalMap& map, const Eigen::MatrixXd& local_cov, VarId start, GlobalMap& global,
						 const SlsjfParams& params, const std::vector<Eigen::Index>& chosen,
						 const std::vector<Anchor>& anchors, MapAssociationOutcome& out)
{
	if (chosen.empty()) return;
	const Eigen::Matrix3d start_cov = global.covariance({start});
	out.extent.start_uncertainty_m = params.overlap_sigmas * largestSigma(start_cov.topLeftCorner<2, 2>());
	// A local feature moves with the start position and, at the map's
	// radius, with its heading: both uncertainties, plus the margin.
	const double slack_m = out.extent.start_uncertainty_m +
		params.overlap_sigmas * std::sqrt(start_cov(2, 2)) * out.extent.radius_m + params.overlap_margin_m;
	std::vector<Eigen::Vector2d> local_features;
	for (const Eigen::Index i : chosen) local_features.push_back(map.features[i].position);
	const auto anchored = [&](VarId v) {
		return std::any_of(anchors.begin(), anchors.end(), [v](const Anchor& a) { return a.global == v; });
	};
	std::vector<VarId> candidates;
	for (const VarId v : overlapCandidates(global, global.pose(start), local_features, out.extent,
										   params.overlap_margin_m, slack_m, out.maps_selected))
		if (!anchored(v)) candidates.push_back(v);
	out.tally.candidates += candidates.size();
	if (candidates.empty()) return;
	const int first_anchor_candidate = static_cast<int>(candidates.size());
	for (const Anchor& a : anchors) candidates.push_back(a.global);

	std::vector<Eigen::Index> observed = chosen;
	for (const Anchor& a : anchors) observed.push_back(a.local);
	PointSets sets;
	sets.observed.resize(static_cast<Eigen::Index>(observed.size()), 2);
	std::vector<Eigen::Index> rows;
	for (std::size_t u = 0; u < observed.size(); ++u)
	{
		sets.observed.row(static_cast<Eigen::Index>(u)) = map.features[observed[u]].position.transpose();
		rows.push_back(3 + 2 * observed[u]);
		rows.push_back(4 + 2 * observed[u]);
	}
	sets.observed_cov = local_cov(rows, rows);
	candidatesInLocalFrame(global, start, candidates, sets);

	const std::vector<int> slots(chosen.begin(), chosen.end());
	std::vector<LandmarkId> candidate_ids;
	for (const VarId v : candidates) candidate_ids.push_back(global.featureId(v));
	applyMapLevelDecisions(decideMapFeaturesGivenAnchors(sets, chosen.size(), first_anchor_candidate, params), slots,
						   candidate_ids, out.decisions, out.tally);
}
}  // namespace

MapAssociationOutcome associateGeometrically(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, std::optional<VarId> start, GlobalMap& global,
	const SlsjfParams& params)
{
	MapAssociationOutcome out;
	out.extent.radius_m = mapRadius(map, local_cov, params.overlap_sigmas);
	for (const auto& f : map.features) out.decisions.associations.push_back({Association::Kind::New, f.id});
	if (!start) return out;
	std::vector<Eigen::Index> all(map.features.size());
	for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Eigen::Index>(i);
	decideGeometrically(map, local_cov, *start, global, params, all, {}, out);
	return out;
}

void associateUnidentifiedGeometrically(const LocalMap& map, const Eigen::MatrixXd& local_cov, VarId start,
										GlobalMap& global, const SlsjfParams& params, MapAssociationOutcome& outcome)
{
	outcome.extent.radius_m = mapRadius(map, local_cov, params.overlap_sigmas);
	std::vector<Eigen::Index> unidentified;
	std::vector<Anchor> anchors;
	for (std::size_t i = 0; i < map.features.size(); ++i)
	{
		const Association& a = outcome.decisions.associations[i];
		if (const auto var = global.featureVar(map.features[i].id))
		{
			if (a.kind == Association::Kind::Matched) anchors.push_back({static_cast<Eigen::Index>(i), *var});
		}
		else if (a.kind == Association::Kind::New)
			unidentified.push_back(static_cast<Eigen::Index>(i));
	}
	decideGeometrically(map, local_cov, start, global, params, unidentified, anchors, outcome);
}

}  // namespace esif::slsjf
