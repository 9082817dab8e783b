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
	Eigen::Vector3d d = a.mean - b.mean;
	d(2) = wrapAngle(d(2));
	return d.dot((a.cov + b.cov).ldlt().solve(d));
}

/// Covariance of a local map's features, the robot marginalised (eq. 4.12).
Eigen::MatrixXd featureCovariance(const LocalMap& map)
{
	const auto n = static_cast<Eigen::Index>(2 * map.features.size());
	return map.covarianceMatrix().bottomRightCorner(n, n);
}
}  // namespace

void DslamLocalMapJoining::start()
{
	global_ = std::make_unique<GlobalFeatureMap>(params_);
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
		// The map before could not be fused (too few usable features, or no
		// pair within its start's reach): join it with this one, in its
		// frame, leaving out of this one a feature the two place apart.
		const auto disagreeing = disagreeingFeatures(pending_->map, maps.map, params_.idGateDistance2());
		maps = joinConsecutive(*pending_, maps, disagreeing);
		tally_.join_features_left_out += disagreeing.size();
		++tally_.maps_merged;
		pending_.reset();
	}
	if (tryFuse(maps, 0, std::nullopt)) return;
	// Sec. 4.4.4 fails: fewer than two of the map's features are in the
	// global map. Join it with the map fused last, through their shared pose,
	// and fuse the two anew (the previous map's features give the pair).
	const auto& fusions = global_->fusions();
	if (!fusions.empty() && fusions.back().f1 >= 0 && joinWithLastFusion(maps)) return;
	pending_ = std::move(maps);
}

bool DslamLocalMapJoining::joinWithLastFusion(const JoinedMaps& maps)
{
	const Fusion& last = global_->fusions().back();
	// A map that places one of the last fusion's features elsewhere is not
	// joined with it: it waits to be joined with the next map, which has
	// not been fused yet (the pending path above, which leaves such a
	// feature out). Joined here without the feature instead, the withdrawn
	// and redone last fusion lost most of its matches on a simulation with
	// misread IDs (docs/plugins/dslam_lmj.md, "Fewer than two common features").
	if (!disagreeingFeatures(last.source.map, maps.map, params_.idGateDistance2()).empty())
	{
		++tally_.joins_refused;
		return false;
	}
	JoinedMaps joined = joinConsecutive(last.source, maps);
	// Decide everything before the last fusion is withdrawn: its features
	// have no information until the joined map is fused, so no covariance
	// could be recovered then.
	std::optional<UpperLevelOutcome> decided;
	if (!last.anchor)
	{
		decided = associateBeforeWithdrawing(joined.map, global_->informedOnlyByLast());
		if (!decided) return false;
	}

	const Fusion withdrawn = global_->withdrawLast();
	tally_.association.features_rejected -= withdrawn.rejected;
	const double withdrawn_seconds = costs_.back().total_s;	 // carried into the joined map's cost
	costs_.pop_back();
	++tally_.maps_merged;
	if (!tryFuse(joined, withdrawn_seconds, std::move(decided)))
		throw std::logic_error("D-SLAM map joining: local maps joined with map " + std::to_string(joined.map.index) +
							   " could not be fused again");  // the checks above rule this out
	return true;
}

std::optional<UpperLevelOutcome> DslamLocalMapJoining::associateBeforeWithdrawing(
	const LocalMap& joined, const std::vector<LandmarkId>& created)
{
	// The association sees the last map's information twice (in the global
	// map and in the joined map), a small over-confidence of the test only.
	// The pair of the update must not be one of the features the last
	// fusion created, and must place the joined map's end within its
	// start's reach.
	auto decided = associate(joined, featureCovariance(joined));
	if (!decided) return std::nullopt;
	keepFeaturesOfWithdrawnFusion(joined, created, *decided);
	if (keepReferencePairInReach(joined, decided->decisions, created) != PairReach::InReach) return std::nullopt;
	return decided;
}

void DslamLocalMapJoining::keepFeaturesOfWithdrawnFusion(
	const LocalMap& joined, const std::vector<LandmarkId>& created, UpperLevelOutcome& decided) const
{
	// A feature only the withdrawn fusion informs (it created it, or carried
	// it for a fusion withdrawn before) has no other information: left
	// out of the joined map's update (rejected by the ID gate, or as
	// ambiguous), it would stay in the global map with none at all, and the
	// next recovery would fail on a singular information matrix. Its global
	// estimate came from this very map, so failing a test against it says
	// nothing about a misread ID or a wrong match: it is kept, matched to
	// itself. So is one the association gave to another global feature
	// (merging the two would leave this one with no information), unless
	// some local feature is matched to it.
	const auto& global_of_local = global_->globalOfLocal();
	std::set<LandmarkId> claimed;
	for (const auto& a : decided.decisions.associations)
		if (a.kind == Association::Kind::Matched) claimed.insert(a.id);
	for (std::size_t i = 0; i < joined.features.size(); ++i)
	{
		auto& a = decided.decisions.associations[i];
		const LandmarkId local = joined.features[i].id;
		const auto known = global_of_local.find(local);
		const LandmarkId global = useIds(joined) ? local : known != global_of_local.end() ? known->second : -1;
		if (std::find(created.begin(), created.end(), global) == created.end()) continue;
		// Matched to itself already, or another local feature is matched to
		// it and informs it (listing it twice in one update is an error).
		if (claimed.count(global)) continue;
		if (a.kind == Association::Kind::Rejected && decided.tally.id_gate_rejected > 0) --decided.tally.id_gate_rejected;
		a = {Association::Kind::Matched, global};
		claimed.insert(global);
	}
}

std::optional<UpperLevelOutcome> DslamLocalMapJoining::associate(const LocalMap& map, const Eigen::MatrixXd& feature_cov)
{
	relative::FeatureMap& global = global_->features();
	if (useIds(map)) return associateByIds(map, feature_cov, global, params_);
	const auto known = knownGlobalIds(map, false, global_->globalOfLocal(), global);
	if (params_.upper_level_frame == UpperLevelFrame::StartPose)
		return associateInStartFrame(map, feature_cov, known, startOf(map), global, params_);
	return associateInPairFrame(map, feature_cov, known, global, params_);
}

bool DslamLocalMapJoining::tryFuse(
	const JoinedMaps& maps, double seconds_before, std::optional<UpperLevelOutcome> decided)
{
	const auto t0 = Clock::now();
	double association_s = 0;
	if (!global_->anchored())
	{
		if (!global_->fuseAnchor(maps)) return false;
	}
	else
	{
		const auto t_association = Clock::now();
		const bool associated_here = !decided;
		if (!decided) decided = associate(maps.map, featureCovariance(maps.map));
		association_s = secondsSince(t_association);
		if (!decided) return false;
		// Decisions handed in (joinWithLastFusion) were checked before the
		// last fusion was withdrawn: the global information is singular
		// until the joined map is fused, and no covariance can be recovered.
		if (associated_here && keepReferencePairInReach(maps.map, decided->decisions) == PairReach::OutOfReach)
		{
			++tally_.fusions_refused;
			return false;
		}
		if (!global_->fuseRelative(maps, decided->decisions)) return false;
		tally_.association += decided->tally;
	}
	tally_.association.features_rejected += global_->fusions().back().rejected;
	tally_.association.seconds += association_s;
	const double seconds = seconds_before + secondsSince(t0);
	costs_.push_back({maps.originals.front(), seconds, association_s, global_->features().featureCount() * 2});
	return true;
}

DslamLocalMapJoining::PairReach DslamLocalMapJoining::keepReferencePairInReach(
	const LocalMap& map, StepReport& decisions, const std::vector<LandmarkId>& excluded)
{
	const double gate = chi2GateBound(params_.reference_pair_chi2_quantile, 3);
	const Eigen::MatrixXd map_cov = map.covarianceMatrix();
	const PoseEstimate reached = composeIndependent(startOf(map), {map.end_pose, map_cov.topLeftCorner<3, 3>()});
	PairReach outcome = PairReach::NoPair;
	while (const auto pair = global_->referencePairOf(map, decisions, excluded))
	{
		// The two estimates are taken as independent, though both hold the
		// map's own end pose: a conservative test, as robotPose()'s.
		if (mahalanobis2(global_->endThroughPair(map, map_cov, decisions, *pair), reached) <= gate)
			return PairReach::InReach;
		for (const int i : {pair->first, pair->second}) decisions.associations[i] = {Association::Kind::Rejected, -1};
		++tally_.reference_pairs_refused;
		outcome = PairReach::OutOfReach;
	}
	return outcome;
}

void DslamLocalMapJoining::finishJoining()
{
	requireConfigured();
	if (pending_) giveUpPendingMap();
	global_->locateAllEnds();
}

void DslamLocalMapJoining::giveUpPendingMap()
{
	// No neighbour is left to join (the log ended on maps that could not be
	// fused): the map cannot be fused (Sec. 4.4.4). It is reported, never
	// dropped silently: its features rejected (associations.txt,
	// da_rejected), counted in local_maps_unjoinable, its end poses carried
	// from the last end pose (the global frame's origin before any).
	global_->addUnjoinable(*pending_);
	tally_.maps_unjoinable += pending_->originals.size();
	pending_.reset();
}

PoseEstimate DslamLocalMapJoining::openMapFrame() const
{
	// The open map starts at the last closed map's end pose: a fused one, or
	// a pending one carried from the last fused.
	const PoseEstimate last = global_->lastEndPose();
	if (!pending_) return last;
	const LocalMap& map = pending_->map;
	return composeIndependent(last, {map.end_pose, map.covarianceMatrix().topLeftCorner<3, 3>()});
}

std::optional<std::size_t> DslamLocalMapJoining::ownFeaturesInGlobalMap(
	const LandmarkEkf& open_map, const std::set<LandmarkId>& own_ids) const
{
	if (params_.upper_level_frame != UpperLevelFrame::StartPose || !global_ || !global_->anchored())
		return std::nullopt;
	return ownFeaturesPlacedInGlobalMap(
		open_map, own_ids, openMapFrame(), global_->features(), params_.gate_chi2_quantile);
}

std::optional<EarlierFeatures> DslamLocalMapJoining::globalFeaturesNearOpenMapStart(double radius_m)
{
	requireConfigured();
	if (!global_->anchored()) return EarlierFeatures{};
	const PoseEstimate start = openMapFrame();
	relative::FeatureMap& global = global_->features();
	EarlierFeatures near;  // in the global frame
	for (const LandmarkId id : global.ids())
		if (global.supported(id) && (global.position(id) - start.mean.head<2>()).norm() <= radius_m) near.ids.push_back(id);
	near.positions.resize(static_cast<Eigen::Index>(2 * near.size()));
	for (std::size_t i = 0; i < near.size(); ++i)
		near.positions.segment<2>(2 * static_cast<Eigen::Index>(i)) = global.position(near.ids[i]);
	near.covariance = near.ids.empty() ? Eigen::MatrixXd(0, 0) : global.covariance(near.ids);
	return near.inFrame(start.mean, start.cov);  // the start independent of the features
}

PoseEstimate DslamLocalMapJoining::startOf(const LocalMap& map) const
{
	PoseEstimate start;	 // map 1 starts at the global origin, known exactly
	if (map.index > 1) start = global_->endPoseOf(map.index - 1).value_or(global_->lastEndPose());
	if (map.link) start = composeIndependent(start, {map.link->delta, map.link->cov});
	return start;
}

std::optional<LandmarkId> DslamLocalMapJoining::globalIdOfOpenFeature(LandmarkId id) const
{
	const bool ids = params_.association == MapAssociationMethod::KnownIds ||
		(params_.association == MapAssociationMethod::Auto && !sawMeasurementWithoutId());
	const relative::FeatureMap& global = global_->features();
	if (ids) return global.supported(id) ? std::optional<LandmarkId>(id) : std::nullopt;
	const auto& global_of_local = global_->globalOfLocal();
	const auto it = global_of_local.find(id);
	if (it != global_of_local.end() && global.supported(it->second)) return it->second;
	return std::nullopt;
}

PoseEstimate DslamLocalMapJoining::robotPose() const
{
	requireConfigured();
	const auto& open = builder().openMap();
	const PoseEstimate local = open.robotPose();
	if (global_->fusions().empty() && !pending_) return local;  // map 1 is the global frame
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
		const PoseEstimate placed =
			robotFromPairs(local.mean, points[a], points[b], local_cov, global_->features().position(g1),
						   global_->features().position(g2), global_->pairCovariance(g1, g2));
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
	return {robotPose(), global_->features().landmarks()};
}

std::vector<PoseEstimate> DslamLocalMapJoining::endPoses() const
{
	requireConfigured();
	return global_->endPoses();
}

StepReport DslamLocalMapJoining::mapReport(std::size_t k) const
{
	requireConfigured();
	const Fusion* fusion = global_->fusionOf(k);
	if (!fusion) return {};
	const Fusion& f = *fusion;
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
	requireConfigured();
	std::vector<SettledFusion> out;
	for (const auto& fusion : global_->fusions())
		out.push_back({fusion.source.map.step_reports, fusion.local_ids, fusion.decisions});
	return out;
}

SparseInformationCore& DslamLocalMapJoining::globalInformation() const
{
	requireConfigured();
	return global_->features().core();
}

std::optional<StateInformation> DslamLocalMapJoining::stateInformation() const
{
	requireConfigured();
	const relative::FeatureMap& global = global_->features();
	if (global.featureCount() == 0) return std::nullopt;
	return global.stateInformation();	 // features only (eq. 4.1)
}

CostFigures DslamLocalMapJoining::costFigures() const
{
	requireConfigured();
	CostFigures c;
	const relative::FeatureMap& global = global_->features();
	const SparseCounters sparse = global.core().counters();
	c.state_dim = 2 * global.featureCount();
	c.poses_in_state = 0;  // features only (eq. 4.1)
	c.info_nnz = sparse.information_nnz;
	c.counters = sparse.list();
	c.counters.emplace_back("local_maps_fused", static_cast<double>(global_->mapsFused()));
	c.counters.emplace_back("local_maps_merged", static_cast<double>(tally_.maps_merged));
	c.counters.emplace_back("join_features_left_out", static_cast<double>(tally_.join_features_left_out));
	c.counters.emplace_back("joins_refused", static_cast<double>(tally_.joins_refused));
	c.counters.emplace_back("fusions_refused", static_cast<double>(tally_.fusions_refused));
	c.counters.emplace_back("reference_pairs_refused", static_cast<double>(tally_.reference_pairs_refused));
	c.counters.emplace_back("local_maps_unjoinable", static_cast<double>(tally_.maps_unjoinable));
	tally_.association.appendCounters(c.counters);
	c.counters.emplace_back("relinearised_terms", static_cast<double>(global_->relinearisedTerms()));
	c.counters.emplace_back("relinearisations_rejected", static_cast<double>(global_->rejectedRelinearisations()));
	appendLocalMapCounters(c.counters);
	return c;
}

}  // namespace esif
