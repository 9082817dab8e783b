#include <esif/association/Chi2.h>
#include <esif/association/DataAssociation.h>
#include <esif/models/RangeBearingModel.h>
#include <esif/relative/RelativeAssociation.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

namespace esif::relative
{
namespace
{
constexpr double kDeg = M_PI / 180.0;

Eigen::Vector2d measurementOf(const RangeBearing& m) { return {m.range_m, m.bearing_rad}; }
}  // namespace

RelativeAssociation::RelativeAssociation(const RelativeAssociationParams& params,
										 const ReferenceRules& reference_rules)
	: params_(params), reference_rules_(reference_rules),
	  new_gate_(chi2Quantile(params.new_landmark_chi2_quantile, 2))
{
}

std::vector<LandmarkId> RelativeAssociation::candidatesFor(const Scan& scan, const Pose2& robot,
														   const FeatureMap& map) const
{
	const Pose2 sensor = toPose2(scan.sensor_on_robot);
	const double max_range = scan.max_range_m > 0 ? scan.max_range_m + params_.candidate_margin_m : INFINITY;
	const double half_fov = scan.fov_rad > 0 ? 0.5 * scan.fov_rad + params_.candidate_margin_deg * kDeg : INFINITY;
	std::vector<LandmarkId> out;
	for (LandmarkId id : map.ids())
	{
		const auto h = predictRangeBearing(robot, sensor, map.position(id));
		// Within the range margin of the sensor the bearing says little (the
		// robot may drive over a feature): such features are always candidates.
		const bool near = h.z(0) <= params_.candidate_margin_m;
		if (near || (h.z(0) <= max_range && std::abs(h.z(1)) <= half_fov)) out.push_back(id);
	}
	return out;
}

StepReport RelativeAssociation::associate(const Scan& scan, const Pose2& robot, const Eigen::Matrix3d& robot_cov,
										  FeatureMap& map)
{
	const auto& ms = scan.measurements;
	const Pose2 sensor = toPose2(scan.sensor_on_robot);
	const auto candidates = candidatesFor(scan, robot, map);
	const Eigen::MatrixXd P_map = candidates.empty() ? Eigen::MatrixXd() : map.covariance(candidates);

	// Hypotheses: predictions with the robot-map cross-covariance taken as zero.
	AssociationInput in;
	in.observations.resize(static_cast<Eigen::Index>(ms.size()), 2);
	for (std::size_t i = 0; i < ms.size(); ++i) in.observations.row(i) = measurementOf(ms[i]).transpose();
	const auto k = static_cast<Eigen::Index>(candidates.size());
	in.predictions.resize(k, 2);
	Eigen::MatrixXd Hr(2 * k, 3), Hf = Eigen::MatrixXd::Zero(2 * k, 2 * k);
	for (Eigen::Index j = 0; j < k; ++j)
	{
		const auto h = predictRangeBearing(robot, sensor, map.position(candidates[j]));
		in.predictions.row(j) = h.z.transpose();
		Hr.middleRows<2>(2 * j) = h.d_robot;
		Hf.block<2, 2>(2 * j, 2 * j) = h.d_landmark;
	}
	in.covariance = Hr * robot_cov * Hr.transpose() + Hf * P_map * Hf.transpose();
	for (Eigen::Index j = 0; j < k && !ms.empty(); ++j) in.covariance.block<2, 2>(2 * j, 2 * j) += ms.front().cov;

	const auto method = params_.association == AssociationMode::NearestNeighbor ? AssociationMethod::NearestNeighbor
																			: AssociationMethod::Jcbb;
	const auto result = esif::associate(in, method, params_.gate_chi2_quantile, params_.search);
	jcbb_nodes_ += result.jcbb_nodes;
	jcbb_fallbacks_ += result.fell_back;

	std::vector<Match> matches;
	std::vector<bool> taken(candidates.size(), false);
	for (std::size_t i = 0; i < ms.size(); ++i)
	{
		const int c = result.candidate_of[i];
		if (c >= 0 && !taken[c])
		{
			taken[c] = true;
			matches.push_back({static_cast<int>(i), c});
		}
	}
	verify(matches, scan, P_map, candidates, map);

	StepReport report;
	report.associations.assign(ms.size(), {Association::Kind::Rejected, -1});
	for (const auto& m : matches) report.associations[m.measurement] = {Association::Kind::Matched, candidates[m.candidate]};
	for (std::size_t i = 0; i < ms.size(); ++i)
		if (result.candidate_of[i] < 0 && result.min_distance2[i] > new_gate_)
			report.associations[i] = {Association::Kind::New, -1};
	return report;
}

double RelativeAssociation::relativeTest(const std::vector<Match>& matches, const Scan& scan,
										 const Eigen::MatrixXd& candidate_cov,
										 const std::vector<LandmarkId>& candidates, const FeatureMap& map) const
{
	const int m = static_cast<int>(matches.size());
	const Pose2 sensor = toPose2(scan.sensor_on_robot);
	// Measured points (eq. 3.41-3.42) and the pair to measure angles from.
	Eigen::VectorXd z(2 * m);
	Eigen::MatrixXd Rz = Eigen::MatrixXd::Zero(2 * m, 2 * m);
	for (int a = 0; a < m; ++a)
	{
		const auto& meas = scan.measurements[matches[a].measurement];
		z.segment<2>(2 * a) = measurementOf(meas);
		Rz.block<2, 2>(2 * a, 2 * a) = meas.cov;
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
	return d2 / chi2Quantile(params_.relative_gate_chi2_quantile, static_cast<int>(nu.size()));	// eq. (3.45)
}

void RelativeAssociation::verify(std::vector<Match>& matches, const Scan& scan, const Eigen::MatrixXd& candidate_cov,
								 const std::vector<LandmarkId>& candidates, const FeatureMap& map)
{
	while (matches.size() >= 2 && relativeTest(matches, scan, candidate_cov, candidates, map) >= 1.0)
	{
		if (matches.size() == 2)
		{
			dropped_ += 2;	// two features disagree on their distance: trust neither
			matches.clear();
			return;
		}
		std::size_t worst = 0;
		double best = std::numeric_limits<double>::infinity();
		for (std::size_t r = 0; r < matches.size(); ++r)
		{
			std::vector<Match> rest = matches;
			rest.erase(rest.begin() + static_cast<long>(r));
			const double t = relativeTest(rest, scan, candidate_cov, candidates, map);
			if (t < best) best = t, worst = r;
		}
		matches.erase(matches.begin() + static_cast<long>(worst));
		++dropped_;
	}
}

}  // namespace esif::relative
