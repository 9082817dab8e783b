#include "DslamLocalMapJoining.h"

#include "PairFrame.h"
#include "ReferenceChoice.h"

#include <esif/association/Chi2.h>
#include <esif/core/Elapsed.h>
#include <esif/core/Errors.h>

#include <algorithm>
#include <chrono>
#include <set>

IMPLEMENTS_MRPT_OBJECT(DslamLocalMapJoining, FilterPlugin, esif)

namespace esif
{
using namespace lmj;

namespace
{
using Clock = SteadyClock;

/// Squared Mahalanobis distance between two estimates of the same robot
/// pose, their errors taken as independent (heading wrapped).
double mahalanobis2(const PoseEstimate& a, const PoseEstimate& b)
{
	Eigen::Vector3d d = toPose2(a.mean) - toPose2(b.mean);
	d(2) = wrapAngle(d(2));
	return d.dot((a.cov + b.cov).ldlt().solve(d));
}

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
}  // namespace

void DslamLocalMapJoining::start()
{
	global_ = std::make_unique<relative::FeatureMap>(params_.recovery);
	global_->shareLinearisationPoints(params_.map_linearisation == relative::MapLinearisation::Shared);
	global_->keepRelativeTerms(params_.relinearise_after_fusion);
}

void DslamLocalMapJoining::requireConfigured() const
{
	if (!global_) throw std::logic_error("DslamLocalMapJoining: used before configure()");
}

void DslamLocalMapJoining::checkGivenMap(const LocalMap& map) const
{
	if (!map.ids_identify_features && map.index > 1)
		throw InputError("D-SLAM map joining: local map " + std::to_string(map.index) +
						 ": its feature IDs are hidden, but the upper-level association needs two features of each "
						 "map known to be in the global map (Sec. 4.4.2); join local-map files with their IDs");
}

bool DslamLocalMapJoining::useIds(const LocalMap& map) const
{
	switch (params_.association)
	{
		case MapAssociationMethod::KnownIds: return true;
		case MapAssociationMethod::Auto: return map.ids_identify_features && !sawMeasurementWithoutId();
		default: return false;
	}
}

void DslamLocalMapJoining::fuseLocalMap(const LocalMap& closed)
{
	requireConfigured();
	std::vector<LandmarkId> ids;
	for (const auto& f : closed.features) ids.push_back(f.id);
	feature_ids_of_map_[closed.index] = ids;

	JoinedMaps maps = single(closed);
	if (pending_)
	{
		// The first map had too few features: join it with this one, in its frame.
		maps = joinConsecutive(*pending_, maps);
		++tally_.maps_merged;
		pending_.reset();
	}
	if (tryFuse(maps, 0, std::nullopt)) return;
	// Sec. 4.4.4 fails: fewer than two of the map's features are in the
	// global map. Join it with the map fused last, through their shared pose,
	// and fuse the two anew (the previous map's features give the pair).
	if (!fusions_.empty() && fusions_.back().f1 >= 0 && joinWithLastFusion(maps)) return;
	pending_ = std::move(maps);
}

bool DslamLocalMapJoining::joinWithLastFusion(const JoinedMaps& maps)
{
	const Fusion& last = fusions_.back();
	const JoinedMaps joined_maps = joinConsecutive(last.source, maps);
	const LocalMap& joined = joined_maps.map;

	// Decide everything before the last fusion is withdrawn: its features
	// have no information until the joined map is fused, so no covariance
	// could be recovered then. The association sees the last map's
	// information twice (in the global map and in the joined map), a small
	// over-confidence of the test only. The pair of the update must not be
	// one of the features the last fusion created.
	std::optional<UpperLevelOutcome> decided;
	if (!last.anchor)
	{
		const auto n = static_cast<int>(joined.features.size());
		decided = associate(joined, joined.covarianceMatrix().bottomRightCorner(2 * n, 2 * n));
		if (!decided) return false;
		const auto& created = last.update.new_features;
		keepFeaturesOfWithdrawnFusion(joined, created, *decided);
		std::vector<Eigen::Vector2d> points;
		std::vector<int> usable;
		for (int i = 0; i < n; ++i)
		{
			points.push_back(joined.features[i].position);
			const auto& a = decided->decisions.associations[i];
			if (a.kind == Association::Kind::Matched && global_->supported(a.id) &&
				std::find(created.begin(), created.end(), a.id) == created.end())
				usable.push_back(i);
		}
		if (!chooseReferenceFeatures(points, usable, params_.reference_min_separation_m,
									 params_.reference_min_clearance_m))
			return false;
	}

	Fusion withdrawn = std::move(fusions_.back());
	fusions_.pop_back();
	global_->withdraw(withdrawn.update);  // its features stay, without its information, until fused again
	if (withdrawn.anchor) anchored_ = false;
	tally_.association.features_rejected -= withdrawn.rejected;
	costs_.pop_back();
	pair_cov_cache_.clear();
	++tally_.maps_merged;
	if (!tryFuse(joined_maps, withdrawn.seconds, std::move(decided)))
		throw std::logic_error("D-SLAM map joining: local maps joined with map " + std::to_string(joined.index) +
							   " could not be fused again");  // the checks above rule this out
	return true;
}

void DslamLocalMapJoining::keepFeaturesOfWithdrawnFusion(
	const LocalMap& joined, const std::vector<LandmarkId>& created, UpperLevelOutcome& decided) const
{
	// A feature the withdrawn fusion created has no other information: left
	// out of the joined map's update (rejected by the ID gate, or as
	// ambiguous), it would stay in the global map with none at all, and the
	// next recovery would fail on a singular information matrix. Its global
	// estimate came from this very map, so failing a test against it says
	// nothing about a misread ID or a wrong match: it is kept, matched to itself.
	for (std::size_t i = 0; i < joined.features.size(); ++i)
	{
		auto& a = decided.decisions.associations[i];
		if (a.kind != Association::Kind::Rejected) continue;
		const LandmarkId local = joined.features[i].id;
		const auto known = global_of_local_.find(local);
		const LandmarkId global = useIds(joined) ? local : known != global_of_local_.end() ? known->second : -1;
		if (std::find(created.begin(), created.end(), global) == created.end()) continue;
		a = {Association::Kind::Matched, global};
		if (decided.tally.id_gate_rejected > 0) --decided.tally.id_gate_rejected;
	}
}

std::optional<UpperLevelOutcome> DslamLocalMapJoining::associate(const LocalMap& map, const Eigen::MatrixXd& feature_cov)
{
	if (useIds(map)) return associateByIds(map, feature_cov, *global_, params_);
	const auto known = knownGlobalIds(map, false, global_of_local_, *global_);
	return associateInPairFrame(map, feature_cov, known, *global_, params_);
}

LandmarkId DslamLocalMapJoining::freshId(LandmarkId proposed, std::vector<LandmarkId>& taken_now)
{
	const LandmarkId id = ids_.allocate(proposed, [&](LandmarkId candidate) {
		return global_->contains(candidate) ||
			   std::find(taken_now.begin(), taken_now.end(), candidate) != taken_now.end();
	});
	taken_now.push_back(id);
	return id;
}

bool DslamLocalMapJoining::tryFuse(
	const JoinedMaps& maps, double seconds_before, std::optional<UpperLevelOutcome> decided)
{
	const auto t0 = Clock::now();
	const LocalMap& map = maps.map;
	const Eigen::MatrixXd P = map.covarianceMatrix();
	const auto n = static_cast<int>(map.features.size());
	const Eigen::MatrixXd P_ff = P.bottomRightCorner(2 * n, 2 * n);	 // the robot marginalised (eq. 4.12)
	std::vector<Eigen::Vector2d> points;
	for (const auto& f : map.features) points.push_back(f.position);

	Fusion fusion;
	fusion.source = maps;
	for (const auto& f : map.features) fusion.local_ids.push_back(f.id);
	std::vector<int> order;	 // local features in update order: [f1, f2, others kept]
	double association_s = 0;
	if (!anchored_)
	{
		// The first map: its features, robot marginalised, are the global map
		// (Sec. 4.3); the only absolute information it ever gets.
		if (n < 2) return false;
		const auto pair = chooseReferenceFeatures(points, [&] {
			std::vector<int> all(n);
			for (int i = 0; i < n; ++i) all[i] = i;
			return all;
		}(), params_.reference_min_separation_m, params_.reference_min_clearance_m);
		if (!pair) return false;
		std::vector<LandmarkId> taken, ids;
		for (const auto& f : map.features)
		{
			// A feature of an anchor withdrawn to be joined keeps its global ID.
			const auto known = global_of_local_.find(f.id);
			ids.push_back(known != global_of_local_.end() && global_->contains(known->second) ? known->second
																							  : freshId(f.id, taken));
			fusion.decisions.associations.push_back({Association::Kind::New, ids.back()});
		}
		relative::PointSet all{map.state().tail(2 * n), P_ff};
		fusion.update = global_->updateAnchor(ids, all);
		fusion.anchor = anchored_ = true;
		order = {pair->first, pair->second};
	}
	else
	{
		const auto t_association = Clock::now();
		auto outcome = decided ? std::move(decided) : associate(map, P_ff);
		association_s = secondsSince(t_association);
		if (!outcome) return false;
		// The reference pair among the kept features already mapped (eq. 4.9).
		std::vector<int> mapped;
		for (int i = 0; i < n; ++i)
			if (const auto& a = outcome->decisions.associations[i];
				a.kind == Association::Kind::Matched && global_->supported(a.id))
				mapped.push_back(i);
		const auto pair = chooseReferenceFeatures(
			points, mapped, params_.reference_min_separation_m, params_.reference_min_clearance_m);
		if (!pair) return false;
		tally_.association += outcome->tally;
		fusion.decisions = outcome->decisions;
		order = {pair->first, pair->second};
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
		fusion.update = global_->updateRelative(ids, kept);
	}
	const Eigen::Vector2d reference = global_->position(fusion.decisions.associations[order[0]].id);
	global_->recover(reference);
	relinearise(reference);

	for (int i = 0; i < n; ++i)
	{
		const auto& a = fusion.decisions.associations[i];
		if (a.kind == Association::Kind::Rejected)
			++fusion.rejected;
		else
			global_of_local_[map.features[i].id] = a.id;
	}
	// Sec. 4.4.1: every original map's end pose through the pair (f1, f2).
	fusion.f1_local = points[order[0]];
	fusion.f2_local = points[order[1]];
	fusion.f1 = fusion.decisions.associations[order[0]].id;
	fusion.f2 = fusion.decisions.associations[order[1]].id;
	pair_cov_cache_.clear();
	recordEnds(fusion, P(robotAndPairRows(order[0], order[1]), robotAndPairRows(order[0], order[1])));
	locateEnds(fusion);
	for (const std::size_t k : maps.originals) fusion_of_map_[k] = fusions_.size();
	tally_.association.features_rejected += fusion.rejected;
	tally_.association.seconds += association_s;
	fusion.seconds = seconds_before + secondsSince(t0);
	costs_.push_back({maps.originals.front(), fusion.seconds, association_s, global_->featureCount() * 2});
	fusions_.push_back(std::move(fusion));
	return true;
}

void DslamLocalMapJoining::relinearise(const Eigen::Vector2d& reference)
{
	// Each map's update (eq. 4.17) is linearised at the estimate before its
	// fusion. A map fused across a long stretch without landmarks, before the
	// loop closes, is linearised metres away from where the loop closure
	// later puts its features: its Jacobian then carries information in the
	// wrong directions, and the map is biased and over-confident (long_gap).
	// Evaluating the updates again at the current estimate is a Gauss-Newton
	// step of the static map problem (no robot, no prediction: nothing is
	// marginalised, so nothing is lost by doing so).
	if (!params_.relinearise_after_fusion) return;
	tally_.relinearised_terms +=
		global_->relineariseUntilSettled(params_.relinearise_threshold_m, params_.relinearise_iterations, reference);
}

void DslamLocalMapJoining::recordEnds(Fusion& fusion, const Eigen::MatrixXd& pair_cov) const
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

void DslamLocalMapJoining::finishJoining()
{
	requireConfigured();
	if (pending_) giveUpPendingMap();
	for (auto& fusion : fusions_) locateEnds(fusion);
}

void DslamLocalMapJoining::giveUpPendingMap()
{
	// No neighbour is left to join (only when the log's first maps never hold
	// two usable features): the map cannot be fused (Sec. 4.4.4). It is
	// reported, never dropped silently: its features rejected
	// (associations.txt, da_rejected), counted in local_maps_unjoinable, its
	// end poses carried from the global frame's origin.
	const LocalMap& map = pending_->map;
	Fusion fusion;
	fusion.source = *pending_;
	for (const auto& f : map.features)
	{
		fusion.local_ids.push_back(f.id);
		fusion.decisions.associations.push_back({Association::Kind::Rejected, -1});
	}
	AbsorbedEnds ends = pending_->absorbed;
	ends.emplace_back(map.end_pose, map.covarianceMatrix().topLeftCorner<3, 3>());
	const std::vector<std::size_t>& originals = pending_->originals;
	for (std::size_t j = 0; j < ends.size(); ++j)
		fusion.ends.push_back({originals[j], ends[j].first, Eigen::MatrixXd(),
							   composeIndependent(lastEndPose(), {toTPose2D(ends[j].first), ends[j].second})});
	tally_.maps_unjoinable += originals.size();
	for (const std::size_t k : originals) fusion_of_map_[k] = fusions_.size();
	fusions_.push_back(std::move(fusion));
	pending_.reset();
}

Eigen::Matrix4d DslamLocalMapJoining::pairCovariance(LandmarkId f1, LandmarkId f2) const
{
	const auto key = std::make_pair(f1, f2);
	if (const auto it = pair_cov_cache_.find(key); it != pair_cov_cache_.end()) return it->second;
	return pair_cov_cache_[key] = global_->covariance({f1, f2});
}

void DslamLocalMapJoining::locateEnds(Fusion& fusion) const
{
	if (fusion.f1 < 0) return;	// a map that could not be fused keeps its carried poses
	const Eigen::Matrix4d G = pairCovariance(fusion.f1, fusion.f2);
	for (auto& end : fusion.ends)
		end.global = robotFromPairs(end.local, fusion.f1_local, fusion.f2_local, end.local_cov,
									global_->position(fusion.f1), global_->position(fusion.f2), G);
}

PoseEstimate DslamLocalMapJoining::lastEndPose() const
{
	if (fusions_.empty()) return {};  // the global frame is map 1's start
	return fusions_.back().ends.back().global;
}

PoseEstimate DslamLocalMapJoining::openMapFrame() const
{
	// The open map starts at the last closed map's end pose: a fused one, or
	// a pending one carried from the last fused.
	const PoseEstimate last = lastEndPose();
	if (!pending_) return last;
	const LocalMap& map = pending_->map;
	return composeIndependent(last, {toTPose2D(map.end_pose), map.covarianceMatrix().topLeftCorner<3, 3>()});
}

std::optional<LandmarkId> DslamLocalMapJoining::globalIdOfOpenFeature(LandmarkId id) const
{
	const bool ids = params_.association == MapAssociationMethod::KnownIds ||
		(params_.association == MapAssociationMethod::Auto && !sawMeasurementWithoutId());
	if (ids) return global_->supported(id) ? std::optional<LandmarkId>(id) : std::nullopt;
	const auto it = global_of_local_.find(id);
	if (it != global_of_local_.end() && global_->supported(it->second)) return it->second;
	return std::nullopt;
}

PoseEstimate DslamLocalMapJoining::robotPose() const
{
	requireConfigured();
	const auto& open = builder().openMap();
	const PoseEstimate local = open.robotPose();
	if (fusions_.empty() && !pending_) return local;  // map 1 is the global frame
	// Sec. 4.4.1: two mapped features of the open map place the robot ...
	std::vector<Eigen::Vector2d> points;
	std::vector<int> mapped;
	std::vector<LandmarkId> global_ids;
	for (std::size_t i = 0; i < open.ids().size(); ++i)
	{
		points.push_back(open.core().landmark(i));
		const auto g = globalIdOfOpenFeature(open.ids()[i]);
		global_ids.push_back(g.value_or(-1));
		if (g) mapped.push_back(static_cast<int>(i));
	}
	// ... else its pose in the open map composed onto the map's start, which
	// also checks every pair.
	const PoseEstimate composed = composeIndependent(openMapFrame(), local);
	const double agree = chi2GateBound(params_.reference_pair_chi2_quantile, 3);
	while (const auto pair = chooseReferenceFeatures(
			   points, mapped, params_.reference_min_separation_m, params_.reference_min_clearance_m))
	{
		const auto [a, b] = *pair;
		const auto rows = robotAndPairRows(a, b);
		const Eigen::MatrixXd local_cov = Eigen::MatrixXd(open.core().covariance())(rows, rows);
		const LandmarkId g1 = global_ids[a], g2 = global_ids[b];
		const PoseEstimate placed = robotFromPairs(toPose2(local.mean), points[a], points[b], local_cov,
												   global_->position(g1), global_->position(g2), pairCovariance(g1, g2));
		// A feature mapped from a misread carries a neighbour's ID: a pair
		// holding it puts the robot metres from where the open map's start
		// puts it (configs/sim/wrong_ids.ini). Such a pair is passed over
		// (reference_pair_chi2_quantile).
		if (mahalanobis2(placed, composed) <= agree) return placed;
		mapped.erase(std::remove_if(mapped.begin(), mapped.end(), [&](int i) { return i == a || i == b; }),
					 mapped.end());
	}
	return composed;
}

Estimate DslamLocalMapJoining::estimate() const
{
	requireConfigured();
	// The global map only: a feature enters it when its map is fused (the
	// book's fusion delay, Sec. 4.6.1).
	return {robotPose(), global_->landmarks()};
}

std::vector<PoseEstimate> DslamLocalMapJoining::endPoses() const
{
	std::map<std::size_t, PoseEstimate> by_map;
	for (const auto& fusion : fusions_)
		for (const auto& end : fusion.ends) by_map[end.map] = end.global;
	std::vector<PoseEstimate> out;
	for (const auto& [k, pose] : by_map) out.push_back(pose);
	return out;
}

StepReport DslamLocalMapJoining::mapReport(std::size_t k) const
{
	const auto fusion = fusion_of_map_.find(k);
	if (fusion == fusion_of_map_.end()) return {};
	const Fusion& f = fusions_[fusion->second];
	StepReport out;
	for (const LandmarkId id : feature_ids_of_map_.at(k))
	{
		const auto at = std::find(f.local_ids.begin(), f.local_ids.end(), id);
		out.associations.push_back(at == f.local_ids.end() ? Association{Association::Kind::Rejected, -1}
														   : f.decisions.associations[at - f.local_ids.begin()]);
	}
	return out;
}

std::vector<MapJoiningPlugin::SettledFusion> DslamLocalMapJoining::settledFusions() const
{
	std::vector<SettledFusion> out;
	for (const auto& fusion : fusions_)
		out.push_back({fusion.source.map.step_reports, fusion.local_ids, fusion.decisions});
	return out;
}

SparseInformationCore& DslamLocalMapJoining::globalInformation() const
{
	requireConfigured();
	return global_->core();
}

std::optional<StateInformation> DslamLocalMapJoining::stateInformation() const
{
	requireConfigured();
	if (global_->featureCount() == 0) return std::nullopt;
	return global_->stateInformation();	 // features only (eq. 4.1)
}

CostFigures DslamLocalMapJoining::costFigures() const
{
	requireConfigured();
	CostFigures c;
	const SparseCounters sparse = global_->core().counters();
	c.state_dim = 2 * global_->featureCount();
	c.poses_in_state = 0;  // features only (eq. 4.1)
	c.info_nnz = sparse.information_nnz;
	c.counters = sparse.list();
	std::size_t fused = 0;
	for (const auto& fusion : fusions_) fused += fusion.f1 >= 0 ? fusion.source.originals.size() : 0;
	c.counters.emplace_back("local_maps_fused", static_cast<double>(fused));
	c.counters.emplace_back("local_maps_merged", static_cast<double>(tally_.maps_merged));
	c.counters.emplace_back("local_maps_unjoinable", static_cast<double>(tally_.maps_unjoinable));
	tally_.association.appendCounters(c.counters);
	c.counters.emplace_back("relinearised_terms", static_cast<double>(tally_.relinearised_terms));
	return c;
}

}  // namespace esif
