#include <esif/association/Ambiguity.h>
#include <esif/association/CandidateWindow.h>
#include <esif/association/Chi2.h>
#include <esif/association/DataAssociation.h>
#include <esif/models/RangeBearingModel.h>
#include <esif/models/Se2.h>
#include <esif/relative/RelativeAssociation.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

namespace esif::relative
{
namespace
{
Eigen::Vector2d measurementOf(const RangeBearing& m) { return {m.range_m, m.bearing_rad}; }
}  // namespace

RelativeAssociation::RelativeAssociation(const RelativeAssociationParams& params,
										 const ReferenceRules& reference_rules)
	: params_(params), reference_rules_(reference_rules),
	  new_gate_(chi2Quantile(params.new_landmark_chi2_quantile, 2)),
	  ambiguity_margin_d2_(ambiguityMarginDistance2(params.ambiguity_margin_chi2_quantile))
{
}

std::vector<LandmarkId> RelativeAssociation::candidatesFor(const Scan& scan, const Pose2& robot,
														   const Eigen::Matrix3d& robot_cov, const FeatureMap& map,
														   const std::unordered_set<LandmarkId>& excluded) const
{
	const Pose2 sensor = scan.sensor_on_robot;
	const CandidateWindow window(scan, params_.candidate_margin_m, params_.candidate_margin_deg);
	std::vector<LandmarkId> out;
	for (LandmarkId id : map.ids())
	{
		if (excluded.count(id)) continue;
		const auto h = predictRangeBearing(robot, sensor, map.position(id));
		const Eigen::Vector2d sd = (h.d_robot * robot_cov * h.d_robot.transpose()).diagonal().cwiseSqrt();
		if (window.admits(h.z, params_.candidate_margin_sigmas * sd)) out.push_back(id);
	}
	return out;
}

AssociationInput RelativeAssociation::absoluteInput(const Scan& scan, const Pose2& robot,
													 const Eigen::Matrix3d& robot_cov, const FeatureMap& map,
													 const std::vector<LandmarkId>& candidates,
													 const Eigen::MatrixXd& candidate_cov)
{
	// Predictions with the robot-map cross-covariance taken as zero (Sec. 3.4.2).
	const auto& ms = scan.measurements;
	const Pose2 sensor = scan.sensor_on_robot;
	const auto k = static_cast<Eigen::Index>(candidates.size());
	AssociationInput in;
	in.observations.resize(static_cast<Eigen::Index>(ms.size()), 2);
	for (std::size_t i = 0; i < ms.size(); ++i) in.observations.row(i) = measurementOf(ms[i]).transpose();
	in.predictions.resize(k, 2);
	Eigen::MatrixXd Hr(2 * k, 3), Hf = Eigen::MatrixXd::Zero(2 * k, 2 * k);
	for (Eigen::Index j = 0; j < k; ++j)
	{
		const auto h = predictRangeBearing(robot, sensor, map.position(candidates[j]));
		in.predictions.row(j) = h.z.transpose();
		Hr.middleRows<2>(2 * j) = h.d_robot;
		Hf.block<2, 2>(2 * j, 2 * j) = h.d_landmark;
	}
	in.covariance = Hr * robot_cov * Hr.transpose() + Hf * candidate_cov * Hf.transpose();
	for (Eigen::Index j = 0; j < k && !ms.empty(); ++j) in.covariance.block<2, 2>(2 * j, 2 * j) += sightingCov(scan, ms.front());
	return in;
}

StepReport RelativeAssociation::associate(const Scan& scan, const Pose2& robot, const Eigen::Matrix3d& robot_cov,
										  FeatureMap& map, const std::unordered_set<LandmarkId>& excluded,
										  const std::vector<Anchor>& anchors)
{
	const auto& ms = scan.measurements;
	const auto candidates = candidatesFor(scan, robot, robot_cov, map, excluded);
	const auto k = static_cast<Eigen::Index>(candidates.size());

	// The relative tests see the candidates and the anchors: measurements
	// [scan, anchors], features [candidates, anchors].
	Scan tested = scan;
	std::vector<LandmarkId> features = candidates;
	std::vector<Match> anchored;
	for (const Anchor& a : anchors)
	{
		anchored.push_back({static_cast<int>(tested.measurements.size()), static_cast<int>(features.size()), true});
		tested.measurements.push_back(a.measurement);
		features.push_back(a.feature);
	}
	const Eigen::MatrixXd P = features.empty() ? Eigen::MatrixXd() : map.covariance(features);
	const Tested t{tested, P, features, map};
	// Tracked features that disagree with the map on their own geometry
	// leave no reference to test hypotheses against: decide nothing. They
	// were tracked, so only a disagreement beyond the new-feature
	// confidence counts (at the relative test's 0.99 one scan in a hundred
	// would be lost to chance).
	if (anchored.size() >= 2 && relativeTest(anchored, t, params_.new_landmark_chi2_quantile) >= 1.0)
	{
		++anchor_conflicts_;
		StepReport none;
		none.associations.assign(ms.size(), {Association::Kind::Rejected, -1});
		return none;
	}

	const AssociationInput in = absoluteInput(scan, robot, robot_cov, map, candidates, P.topLeftCorner(2 * k, 2 * k));

	// With anchors the hypotheses come from the relative test itself: the
	// absolute gate, robot and map independent, passes a whole grid row
	// shifted by one spacing after dead reckoning, and JCBB then prefers it.
	const Eigen::MatrixXd d2 = individualDistances2(in);
	std::vector<int> candidate_of;
	if (!anchored.empty())
		candidate_of = bestFitsToAnchors(d2, anchored, t);
	else
	{
		const auto method = params_.association == AssociationMode::NearestNeighbor ? AssociationMethod::NearestNeighbor
																				: AssociationMethod::Jcbb;
		const auto result = esif::associate(in, method, params_.gate_chi2_quantile, params_.search);
		jcbb_nodes_ += result.jcbb_nodes;
		jcbb_fallbacks_ += result.fell_back;
		candidate_of = result.candidate_of;
	}

	std::vector<Match> matches = anchored;
	std::vector<bool> taken(candidates.size(), false);
	for (std::size_t i = 0; i < ms.size(); ++i)
	{
		const int c = candidate_of[i];
		if (c >= 0 && !taken[c])
		{
			taken[c] = true;
			matches.push_back({static_cast<int>(i), c, false});
		}
	}
	verify(matches, t);
	dropUncheckedAmbiguousMatch(matches, in, d2, scan);

	StepReport report;
	report.associations.assign(ms.size(), {Association::Kind::Rejected, -1});
	for (const auto& m : matches)
		if (!m.anchor) report.associations[m.measurement] = {Association::Kind::Matched, candidates[m.candidate]};
	for (std::size_t i = 0; i < ms.size(); ++i)
	{
		if (report.associations[i].kind == Association::Kind::Matched) continue;
		// Unmatched, or matched and dropped by the relative test.
		const bool far = candidate_of[i] < 0 && (k == 0 || d2.row(static_cast<Eigen::Index>(i)).minCoeff() > new_gate_);
		if (far || noCandidateFitsAnchors(static_cast<int>(i), d2, anchored, matches, t))
			report.associations[i] = {Association::Kind::New, -1};
	}
	return report;
}

void RelativeAssociation::dropUncheckedAmbiguousMatch(
	std::vector<Match>& matches, const AssociationInput& in, const Eigen::MatrixXd& d2, const Scan& scan)
{
	if (matches.size() != 1 || matches.front().anchor) return;	// checked by eq. (3.45), or nothing to check
	const Eigen::Index i = matches.front().measurement, c = matches.front().candidate;
	const Eigen::LLT<Eigen::Matrix2d> noise(sightingCov(scan, scan.measurements[static_cast<std::size_t>(i)]));
	const bool ambiguous = ambiguousMatch(d2.row(i).transpose(), c, ambiguity_margin_d2_, [&](Eigen::Index j) {
		Eigen::Vector2d dz = (in.predictions.row(j) - in.predictions.row(c)).transpose();
		dz(1) = wrapAngle(dz(1));
		return dz.dot(noise.solve(dz));
	});
	if (ambiguous) matches.clear(), ++ambiguous_waits_;
}

std::vector<int> RelativeAssociation::bestFitsToAnchors(const Eigen::MatrixXd& d2, const std::vector<Match>& anchored,
														const Tested& t) const
{
	// Per measurement, the candidate inside the individual gate whose
	// relative test with the anchors, eq. (3.45), is smallest and passes; a
	// candidate claimed twice goes to the better fit. verify() then tests
	// the set jointly.
	const double gate = chi2Quantile(params_.gate_chi2_quantile, 2);
	const auto n = d2.rows(), k = d2.cols();
	std::vector<int> best(static_cast<std::size_t>(n), -1);
	std::vector<double> fit(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
	for (Eigen::Index i = 0; i < n; ++i)
		for (Eigen::Index j = 0; j < k; ++j)
		{
			if (d2(i, j) > gate) continue;
			const double r = relativeTestWithAnchors(anchored, static_cast<int>(i), static_cast<int>(j), t);
			// Ranked by both statistics: with one anchor the relative test
			// holds a distance only, which a grid repeats.
			const double score = d2(i, j) / gate + r;
			if (r < 1.0 && score < fit[i]) fit[i] = score, best[i] = static_cast<int>(j);
		}
	for (Eigen::Index i = 0; i < n; ++i)
		for (Eigen::Index o = 0; o < n; ++o)
			if (o != i && best[i] >= 0 && best[o] == best[i] && fit[o] < fit[i]) best[i] = -1;
	return best;
}

bool RelativeAssociation::noCandidateFitsAnchors(int measurement, const Eigen::MatrixXd& d2,
												 const std::vector<Match>& anchored, const std::vector<Match>& accepted,
												 const Tested& t) const
{
	// Near a candidate in absolute terms, which after dead reckoning says
	// little: new when no such candidate fits the features tracked in this
	// scan (the anchors) in relative distances and angles, eq. (3.45).
	if (anchored.empty()) return false;
	for (Eigen::Index j = 0; j < d2.cols(); ++j)
	{
		if (d2(measurement, j) > new_gate_) continue;
		const bool used = std::any_of(accepted.begin(), accepted.end(),
									  [&](const Match& m) { return !m.anchor && m.candidate == j; });
		if (used) return false;	 // another measurement took it: ambiguous
		if (relativeTestWithAnchors(anchored, measurement, static_cast<int>(j), t) < 1.0) return false;
	}
	return true;
}

double RelativeAssociation::relativeTestWithAnchors(const std::vector<Match>& anchored, int measurement, int candidate,
													 const Tested& t) const
{
	std::vector<Match> hypothesis = anchored;
	hypothesis.push_back({measurement, candidate, false});
	return relativeTest(hypothesis, t);
}

double RelativeAssociation::relativeTest(const std::vector<Match>& matches, const Tested& t, double quantile) const
{
	const Scan& scan = t.scan;
	const Eigen::MatrixXd& candidate_cov = t.cov;
	const std::vector<LandmarkId>& candidates = t.features;
	const FeatureMap& map = t.map;
	const int m = static_cast<int>(matches.size());
	const Pose2 sensor = scan.sensor_on_robot;
	// Measured points (eq. 3.41-3.42) and the pair to measure angles from.
	Eigen::VectorXd z(2 * m);
	Eigen::MatrixXd Rz = Eigen::MatrixXd::Zero(2 * m, 2 * m);
	for (int a = 0; a < m; ++a)
	{
		const auto& meas = scan.measurements[matches[a].measurement];
		z.segment<2>(2 * a) = measurementOf(meas);
		Rz.block<2, 2>(2 * a, 2 * a) = sightingCov(scan, meas);
	}
	const PointSet seen = pointsInRobotFrame(z, Rz, sensor);
	std::vector<ReferenceCandidate> refs(m);
	for (int a = 0; a < m; ++a) refs[a] = {seen.point(a), map.mappedOrder(candidates[matches[a].candidate])};
	const ReferenceRules& rules = reference_rules_;
	auto pair = chooseReferencePair(refs, rules);
	if (!pair) pair = chooseReferencePair(refs, {rules.policy, 0.0, 0.0});
	if (!pair) return 0.0;	// coincident points: nothing to test

	// Order [f1, f2, others] on both sides.
	std::vector<int> order = {pair->first, pair->second};
	for (int a = 0; a < m; ++a)
		if (a != pair->first && a != pair->second) order.push_back(a);
	Eigen::VectorXd pts(2 * m), map_xy(2 * m);
	Eigen::MatrixXd pts_cov(2 * m, 2 * m), map_cov(2 * m, 2 * m);
	for (int a = 0; a < m; ++a)
	{
		pts.segment<2>(2 * a) = seen.point(order[a]);
		map_xy.segment<2>(2 * a) = map.position(candidates[matches[order[a]].candidate]);
		for (int b = 0; b < m; ++b)
		{
			pts_cov.block<2, 2>(2 * a, 2 * b) = seen.cov.block<2, 2>(2 * order[a], 2 * order[b]);
			map_cov.block<2, 2>(2 * a, 2 * b) = candidate_cov.block<2, 2>(2 * matches[order[a]].candidate,
																		   2 * matches[order[b]].candidate);
		}
	}
	// Eq. (3.40)-(3.44).
	const ValueJacobian G = relativeGeometry(map_xy), H = relativeGeometry(pts);
	const Eigen::VectorXd nu = relativeDifference(G.value, H.value);
	const Eigen::MatrixXd S =
		G.jacobian * map_cov * G.jacobian.transpose() + H.jacobian * pts_cov * H.jacobian.transpose();
	const Eigen::LDLT<Eigen::MatrixXd> ldlt(S);
	const double d2 = nu.dot(ldlt.solve(nu));
	const double q = quantile > 0 ? quantile : params_.relative_gate_chi2_quantile;
	return d2 / chi2Quantile(q, static_cast<int>(nu.size()));	// eq. (3.45)
}

void RelativeAssociation::verify(std::vector<Match>& matches, const Tested& t)
{
	const auto anchors = static_cast<std::size_t>(
		std::count_if(matches.begin(), matches.end(), [](const Match& m) { return m.anchor; }));
	while (matches.size() > anchors && matches.size() >= 2 && relativeTest(matches, t) >= 1.0)
	{
		if (matches.size() == 2 && anchors == 0)
		{
			dropped_ += 2;	// two features disagree on their distance: trust neither
			matches.clear();
			return;
		}
		// Drop the map match whose removal best restores consistency; the
		// anchors, tracked with their correlation to the robot, stay.
		std::size_t worst = 0;
		double best = std::numeric_limits<double>::infinity();
		for (std::size_t r = 0; r < matches.size(); ++r)
		{
			if (matches[r].anchor) continue;
			std::vector<Match> rest = matches;
			rest.erase(rest.begin() + static_cast<long>(r));
			const double test = rest.size() >= 2 ? relativeTest(rest, t) : 0.0;
			if (test < best) best = test, worst = r;
		}
		matches.erase(matches.begin() + static_cast<long>(worst));
		++dropped_;
	}
}

}  // namespace esif::relative
