#include "GlobalFeatureMap.h"

#include "PairFrame.h"
#include "ReferenceChoice.h"

#include <algorithm>
#include <set>

namespace esif::lmj
{
namespace
{
/// Rows of the features' block [x1, y1, x2, y2, ...] for `features`.
std::vector<Eigen::Index> featureRows(const std::vector<int>& features)
{
	std::vector<Eigen::Index> rows;
	for (const int i : features)
	{
		rows.push_back(2 * i);
		rows.push_back(2 * i + 1);
	}
	return rows;
}

std::vector<Eigen::Vector2d> featurePoints(const LocalMap& map)
{
	std::vector<Eigen::Vector2d> points;
	for (const auto& f : map.features) points.push_back(f.position);
	return points;
}
}  // namespace

GlobalFeatureMap::GlobalFeatureMap(const DslamLmjParams& params)
	: map_(params.recovery),
	  reference_min_separation_m_(params.reference_min_separation_m),
	  reference_min_clearance_m_(params.reference_min_clearance_m),
	  relinearise_after_fusion_(params.relinearise_after_fusion),
	  relinearise_threshold_m_(params.relinearise_threshold_m),
	  relinearise_iterations_(params.relinearise_iterations)
{
	map_.shareLinearisationPoints(params.map_linearisation == relative::MapLinearisation::Shared);
	map_.keepRelativeTerms(params.relinearise_after_fusion);
}

std::optional<std::pair<int, int>> GlobalFeatureMap::referencePair(
	const std::vector<Eigen::Vector2d>& points, const std::vector<int>& eligible) const
{
	return chooseReferenceFeatures(points, eligible, reference_min_separation_m_, reference_min_clearance_m_);
}

Fusion GlobalFeatureMap::openRecord(const JoinedMaps& maps)
{
	Fusion fusion;
	fusion.source = maps;
	for (const auto& f : maps.map.features) fusion.local_ids.push_back(f.id);
	return fusion;
}

LandmarkId GlobalFeatureMap::freshId(LandmarkId proposed, std::vector<LandmarkId>& taken_now)
{
	const LandmarkId id = ids_.allocate(proposed, [&](LandmarkId candidate) {
		return map_.contains(candidate) || std::find(taken_now.begin(), taken_now.end(), candidate) != taken_now.end();
	});
	taken_now.push_back(id);
	return id;
}

bool GlobalFeatureMap::fuseAnchor(const JoinedMaps& maps)
{
	const LocalMap& map = maps.map;
	const Eigen::MatrixXd P = map.covarianceMatrix();
	const auto n = static_cast<int>(map.features.size());
	// The first map: its features, robot marginalised, are the global map
	// (Sec. 4.3); the only absolute information it ever gets.
	if (n < 2) return false;
	std::vector<int> all(n);
	for (int i = 0; i < n; ++i) all[i] = i;
	const auto pair = referencePair(featurePoints(map), all);
	if (!pair) return false;
	Fusion fusion = openRecord(maps);
	std::vector<LandmarkId> taken, ids;
	for (const auto& f : map.features)
	{
		// A feature of an anchor withdrawn to be joined keeps its global ID.
		const auto known = global_of_local_.find(f.id);
		ids.push_back(known != global_of_local_.end() && map_.contains(known->second) ? known->second
																					  : freshId(f.id, taken));
		fusion.decisions.associations.push_back({Association::Kind::New, ids.back()});
	}
	relative::PointSet points{map.state().tail(2 * n), P.bottomRightCorner(2 * n, 2 * n)};
	fusion.update = map_.updateAnchor(ids, points);
	fusion.anchor = anchored_ = true;
	settle(std::move(fusion), {pair->first, pair->second}, P);
	return true;
}

bool GlobalFeatureMap::fuseRelative(const JoinedMaps& maps, const StepReport& decisions)
{
	const LocalMap& map = maps.map;
	const Eigen::MatrixXd P = map.covarianceMatrix();
	const auto n = static_cast<int>(map.features.size());
	const Eigen::MatrixXd P_ff = P.bottomRightCorner(2 * n, 2 * n);	 // the robot marginalised (eq. 4.12)
	const std::vector<Eigen::Vector2d> points = featurePoints(map);
	const auto pair = referencePairOf(map, decisions);
	if (!pair) return false;

	Fusion fusion = openRecord(maps);
	fusion.decisions = decisions;
	std::vector<int> order = {pair->first, pair->second};  // kept features in update order: [f1, f2, others]
	std::vector<LandmarkId> taken;
	for (int i = 0; i < n; ++i)
	{
		auto& a = fusion.decisions.associations[i];
		if (a.kind == Association::Kind::Rejected) continue;
		if (a.kind == Association::Kind::New) a.id = freshId(a.id, taken);
		if (i != pair->first && i != pair->second) order.push_back(i);
	}
	// Eq. 4.10-4.17: z_map of the kept features about (f1, f2), R_map =
	// J P_ff J^T, new features by eq. 4.16, the EIF update.
	std::vector<LandmarkId> ids;
	relative::PointSet kept{Eigen::VectorXd(2 * order.size()), P_ff(featureRows(order), featureRows(order))};
	for (std::size_t j = 0; j < order.size(); ++j)
	{
		ids.push_back(fusion.decisions.associations[order[j]].id);
		kept.xy.segment<2>(2 * j) = points[order[j]];
	}
	fusion.update = map_.updateRelative(ids, kept);
	settle(std::move(fusion), order, P);
	return true;
}

std::optional<std::pair<int, int>> GlobalFeatureMap::referencePairOf(
	const LocalMap& map, const StepReport& decisions, const std::vector<LandmarkId>& excluded) const
{
	std::vector<int> mapped;
	for (std::size_t i = 0; i < map.features.size(); ++i)
		if (const auto& a = decisions.associations[i]; a.kind == Association::Kind::Matched && map_.supported(a.id) &&
			std::find(excluded.begin(), excluded.end(), a.id) == excluded.end())
			mapped.push_back(static_cast<int>(i));
	return referencePair(featurePoints(map), mapped);
}

PoseEstimate GlobalFeatureMap::endThroughPair(const LocalMap& map, const Eigen::MatrixXd& map_cov,
											  const StepReport& decisions, std::pair<int, int> pair)
{
	const auto [a, b] = pair;
	const LandmarkId g1 = decisions.associations[a].id, g2 = decisions.associations[b].id;
	const auto rows = robotAndPairRows(a, b);
	return robotFromPairs(map.end_pose, map.features[a].position, map.features[b].position, map_cov(rows, rows),
						  map_.position(g1), map_.position(g2), pairCovariance(g1, g2));
}

void GlobalFeatureMap::settle(Fusion fusion, const std::vector<int>& order, const Eigen::MatrixXd& P)
{
	const Eigen::Vector2d reference = map_.position(fusion.decisions.associations[order[0]].id);
	map_.recover(reference);
	relinearise(reference);

	const auto& features = fusion.source.map.features;
	for (std::size_t i = 0; i < features.size(); ++i)
	{
		const auto& a = fusion.decisions.associations[i];
		if (a.kind == Association::Kind::Rejected)
			++fusion.rejected;
		else
			global_of_local_[features[i].id] = a.id;
	}
	// Sec. 4.4.1: every original map's end pose through the pair (f1, f2).
	fusion.f1_local = features[order[0]].position;
	fusion.f2_local = features[order[1]].position;
	fusion.f1 = fusion.decisions.associations[order[0]].id;
	fusion.f2 = fusion.decisions.associations[order[1]].id;
	pair_cov_cache_.clear();
	const auto rows = robotAndPairRows(order[0], order[1]);
	recordEnds(fusion, P(rows, rows));
	locateEnds(fusion);
	for (const std::size_t k : fusion.source.originals) fusion_of_map_[k] = fusions_.size();
	fusions_.push_back(std::move(fusion));
}

void GlobalFeatureMap::relinearise(const Eigen::Vector2d& reference)
{
	// Each map's update (eq. 4.17) is linearised at the estimate before its
	// fusion. A map fused across a long stretch without landmarks, before the
	// loop closes, is linearised metres away from where the loop closure
	// later puts its features: its Jacobian then carries information in the
	// wrong directions, and the map is biased and over-confident (long_gap).
	// Evaluating the updates again at the current estimate is a Gauss-Newton
	// step of the static map problem (no robot, no prediction: nothing is
	// marginalised, so nothing is lost by doing so).
	if (!relinearise_after_fusion_) return;
	relinearised_terms_ += map_.relineariseUntilSettled(relinearise_threshold_m_, relinearise_iterations_, reference);
}

void GlobalFeatureMap::recordEnds(Fusion& fusion, const Eigen::MatrixXd& pair_cov)
{
	// An absorbed map's end pose: its own covariance, the pair's from the
	// joined map (their correlation is not kept by the join).
	for (const auto& [pose, cov] : fusion.source.absorbed)
	{
		Eigen::MatrixXd local_cov = pair_cov;
		local_cov.topRightCorner<3, 4>().setZero();
		local_cov.bottomLeftCorner<4, 3>().setZero();
		local_cov.topLeftCorner<3, 3>() = cov;
		fusion.ends.push_back({0, pose, local_cov, {}});
	}
	fusion.ends.push_back({0, fusion.source.map.end_pose, pair_cov, {}});
	for (std::size_t j = 0; j < fusion.ends.size(); ++j) fusion.ends[j].map = fusion.source.originals[j];
}

void GlobalFeatureMap::locateEnds(Fusion& fusion)
{
	if (fusion.f1 < 0) return;	// a map that could not be fused keeps its carried poses
	const Eigen::Matrix4d G = pairCovariance(fusion.f1, fusion.f2);
	const Eigen::Vector2d f1 = map_.position(fusion.f1), f2 = map_.position(fusion.f2);
	for (auto& end : fusion.ends)
		end.global = robotFromPairs(end.local, fusion.f1_local, fusion.f2_local, end.local_cov, f1, f2, G);
}

void GlobalFeatureMap::locateAllEnds()
{
	for (auto& fusion : fusions_) locateEnds(fusion);
}

std::vector<LandmarkId> GlobalFeatureMap::informedOnlyByLast() const
{
	if (fusions_.empty()) return {};
	std::set<LandmarkId> by_others;
	for (std::size_t f = 0; f + 1 < fusions_.size(); ++f)
		for (const auto& a : fusions_[f].decisions.associations)
			if (a.kind != Association::Kind::Rejected) by_others.insert(a.id);
	std::vector<LandmarkId> out;
	for (const auto& a : fusions_.back().decisions.associations)
		if (a.kind != Association::Kind::Rejected && !by_others.count(a.id)) out.push_back(a.id);
	return out;
}

Fusion GlobalFeatureMap::withdrawLast()
{
	Fusion withdrawn = std::move(fusions_.back());
	fusions_.pop_back();
	map_.withdraw(withdrawn.update);  // its features stay, without its information, until fused again
	if (withdrawn.anchor) anchored_ = false;
	pair_cov_cache_.clear();
	return withdrawn;
}

void GlobalFeatureMap::addUnjoinable(const JoinedMaps& maps)
{
	Fusion fusion = openRecord(maps);
	for (std::size_t i = 0; i < maps.map.features.size(); ++i)
		fusion.decisions.associations.push_back({Association::Kind::Rejected, -1});
	AbsorbedEnds ends = maps.absorbed;
	ends.emplace_back(maps.map.end_pose, maps.map.covarianceMatrix().topLeftCorner<3, 3>());
	for (std::size_t j = 0; j < ends.size(); ++j)
		fusion.ends.push_back({maps.originals[j], ends[j].first, Eigen::MatrixXd(),
							   composeIndependent(lastEndPose(), {ends[j].first, ends[j].second})});
	for (const std::size_t k : maps.originals) fusion_of_map_[k] = fusions_.size();
	fusions_.push_back(std::move(fusion));
}

Eigen::Matrix4d GlobalFeatureMap::pairCovariance(LandmarkId f1, LandmarkId f2)
{
	const auto key = std::make_pair(f1, f2);
	if (const auto it = pair_cov_cache_.find(key); it != pair_cov_cache_.end()) return it->second;
	return pair_cov_cache_[key] = map_.covariance({f1, f2});
}

const Fusion* GlobalFeatureMap::fusionOf(std::size_t k) const
{
	const auto it = fusion_of_map_.find(k);
	return it == fusion_of_map_.end() ? nullptr : &fusions_[it->second];
}

PoseEstimate GlobalFeatureMap::lastEndPose() const
{
	if (fusions_.empty()) return {};  // the global frame is map 1's start
	return fusions_.back().ends.back().global;
}

std::optional<PoseEstimate> GlobalFeatureMap::endPoseOf(std::size_t k) const
{
	const Fusion* fusion = fusionOf(k);
	if (!fusion) return std::nullopt;
	for (const auto& end : fusion->ends)
		if (end.map == k) return end.global;
	return std::nullopt;
}

std::vector<PoseEstimate> GlobalFeatureMap::endPoses() const
{
	std::map<std::size_t, PoseEstimate> by_map;
	for (const auto& fusion : fusions_)
		for (const auto& end : fusion.ends) by_map[end.map] = end.global;
	std::vector<PoseEstimate> out;
	for (const auto& [k, pose] : by_map) out.push_back(pose);
	return out;
}

std::size_t GlobalFeatureMap::mapsFused() const
{
	std::size_t fused = 0;
	for (const auto& fusion : fusions_) fused += fusion.f1 >= 0 ? fusion.source.originals.size() : 0;
	return fused;
}

}  // namespace esif::lmj
