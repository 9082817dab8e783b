#include "Dslam.h"

#include "CovarianceIntersection.h"
#include "HeldFeatureTracking.h"
#include "KidnappedRobot.h"
#include "OutlierGate.h"

#include <esif/association/Chi2.h>
#include <esif/core/Errors.h>
#include <esif/core/MeasurementSubset.h>
#include <esif/models/RangeBearingModel.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

IMPLEMENTS_MRPT_OBJECT(Dslam, FilterPlugin, esif)

namespace esif
{
using namespace dslam;
using namespace relative;

void Dslam::start()
{
	local_ = LocalSlam(params_.local_hold_steps);
	map_ = std::make_unique<FeatureMap>(params_.recovery);
	association_ = std::make_unique<RelativeAssociation>(params_.association, params_.referenceRules());
	guard_ = DivergenceGuard(params_.divergence_factor, params_.divergence_disagreeing_scans);
	if (params_.confirm_new_features)
		confirmation_.emplace(chi2GateBound(params_.outlier_chi2_quantile, 2),
							  static_cast<std::size_t>(params_.confirmation_window_steps));
	map_->keepRelativeTerms(params_.relinearise_every_steps > 0 || params_.relinearise_on_correction_m > 0);
	map_->shareLinearisationPoints(params_.map_linearisation == MapLinearisation::Shared);
}

StepReport Dslam::processStep(const StepInput& step)
{
	if (!map_) throw std::logic_error("Dslam: processStep() before configure()");
	if (step.odometry)
	{
		local_.predict(*step.odometry);	 // Fig. 3.4, A -> B
		chain_.predict(*step.odometry);
		guard_.travel(*step.odometry);
	}
	if (!step.scan || step.scan->measurements.empty()) return {};
	guard_.sense(*step.scan);

	const Pose2 sensor = step.scan->sensor_on_robot;
	StepReport report = associateScan(step);
	if (params_.admissible == AdmissiblePolicy::Skip && !chain_.rootIsMapFrame() && !observed(*step.scan, report).pair)
	{
		// Skip policy: an inadmissible scan starts no feature; its matches still localise.
		for (auto& a : report.associations)
			if (a.kind == Association::Kind::New) a = {};
	}
	const bool anchoring = chain_.rootIsMapFrame() && chain_.scans() < params_.anchor_scans;
	if (confirmation_ && !anchoring) holdFirstSightings(step, report);
	nameNewFeatures(report);
	if (params_.outlier_chi2_quantile < 1) rejectOutliers(*step.scan, report);
	const Observed obs = observed(*step.scan, report);
	if (obs.all.empty()) return report;

	localize(obs, sensor);
	updateAndRecoverMap(obs, sensor);
	if (params_.relinearise_every_steps > 0 && ++steps_since_relinearisation_ >= params_.relinearise_every_steps)
		relinearise(1);
	guard_.check(map_->ids(), map_->core().state(), local_.robot());
	return report;
}

void Dslam::relinearise(int passes)
{
	tally_.relinearised_terms +=
		map_->relineariseUntilSettled(params_.relinearise_threshold_m, passes, local_.robot().head<2>());
	steps_since_relinearisation_ = 0;
	++tally_.relinearisations;
}

void Dslam::updateAndRecoverMap(const Observed& obs, const Pose2& sensor)
{
	// The relative geometry of the mapped features this scan sees, before
	// and after the update.
	std::vector<LandmarkId> seen;
	for (const auto& m : obs.all)
		if (map_->contains(m.id)) seen.push_back(m.id);
	const Eigen::VectorXd before = map_->positions(seen);

	updateMap(obs, sensor);
	map_->recover(local_.robot().head<2>());
	if (params_.relinearise_on_correction_m <= 0 || seen.size() < 2 ||
		map_->relativeChangeSince(seen, before) <= params_.relinearise_on_correction_m)
		return;
	++tally_.corrections_relinearised;
	relinearise(params_.relinearise_iterations);
}

void Dslam::reserveLandmarkIds(LandmarkId largest_input_id)
{
	next_own_id_ = std::max(next_own_id_, largest_input_id + 1);
}

void Dslam::finish()
{
	if (params_.relinearise_every_steps > 0 && map_ && map_->featureCount() > 0) relinearise(1);
}

StepReport Dslam::associateScan(const StepInput& step)
{
	const auto& ms = step.scan->measurements;
	const bool all_have_ids = std::all_of(ms.begin(), ms.end(), [](const RangeBearing& m) { return m.id.has_value(); });
	associated_by_ids_ = params_.association.association == AssociationMode::KnownIds ||
		(params_.association.association == AssociationMode::Auto && all_have_ids);
	return associated_by_ids_ ? associateByIds(step) : associateByTrackingThenMap(*step.scan);
}

StepReport Dslam::associateByTrackingThenMap(const Scan& scan)
{
	const auto& assoc = params_.association;
	const auto tracked = trackHeldFeatures(local_, scan, assoc.association != AssociationMode::NearestNeighbor,
										   assoc.gate_chi2_quantile,
										   CandidateWindow(scan, assoc.candidate_margin_m, assoc.candidate_margin_deg),
										   assoc.search);
	std::vector<RelativeAssociation::Anchor> anchors;
	StepReport report;
	report.associations.assign(scan.measurements.size(), {Association::Kind::Rejected, -1});
	for (std::size_t i = 0; i < tracked.size(); ++i)
		if (const auto id = tracked[i].feature)
		{
			// A held feature is usually mapped; one still waiting in the chain is not.
			report.associations[i] = {map_->contains(*id) ? Association::Kind::Matched : Association::Kind::New, *id};
			if (map_->supported(*id)) anchors.push_back({scan.measurements[i], *id});
			++tally_.tracked_matches;
		}
	const MeasurementSubset rest =
		measurementSubset(scan, [&](std::size_t i, const RangeBearing&) { return !tracked[i].feature; });
	if (rest.kept.empty()) return report;

	// What tracking left matched none of the held features in view. No held
	// feature is a candidate here: the map-level gate, robot and map
	// independent, is far looser than tracking's and took new features for
	// held neighbours (after long_gap's first crossing, half of all
	// measurements were lost that way). The tracked mapped features anchor
	// its relative tests.
	// With fewer than two tracked anchors a lone sighting has nothing to be
	// checked against: features held out of view stand in.
	const std::unordered_set<LandmarkId> held(local_.order().begin(), local_.order().end());
	if (params_.local_hold_steps > 0 && params_.held_anchor_max_sd_m > 0 && anchors.size() < 2)
		addHeldAnchors(scan, tracked, anchors);
	const StepReport from_map =
		association_->associate(rest.scan, local_.robot(), local_.robotCov(), *map_, held, anchors);
	const double new_gate = chi2Quantile(assoc.new_landmark_chi2_quantile, 2);
	for (std::size_t j = 0; j < rest.kept.size(); ++j)
	{
		const std::size_t i = rest.kept[j];
		const Association& a = from_map.associations[j];
		// Close to a held feature it did not match: ambiguous, not new. Left
		// unassociated rather than given to that feature: matching such
		// near-misses (at the 0.999 or 0.9999 gate) made long_gap diverge at
		// step 1756; leaving them costs grid196 about 1% of its sightings.
		const bool ambiguous = a.kind == Association::Kind::New && tracked[i].min_distance2 <= new_gate;
		if (!ambiguous) report.associations[i] = a;
	}
	return report;
}

void Dslam::addHeldAnchors(const Scan& scan, const std::vector<TrackedMeasurement>& tracked,
						   std::vector<RelativeAssociation::Anchor>& anchors) const
{
	// A mapped feature the local SLAM holds out of view (local_hold_steps)
	// anchors the relative tests as a tracked one does, through its local
	// estimate in the robot frame: the local SLAM's relative geometry is as
	// independent of the robot's error in the map as a measurement. Each
	// anchor carries its own H P H^T, the robot's uncertainty relative to it
	// included; those known no better than held_anchor_max_sd_m (larger of
	// the range and bearing-times-range standard deviations) are left out.
	// The anchors are taken as independent of one another (one robot error
	// moves them all): jointly, they were measured worse on Victoria Park
	// (docs/plugins/dslam.md, "Holding features out of view").
	std::unordered_set<LandmarkId> in_scan;
	for (const auto& t : tracked)
		if (t.feature) in_scan.insert(*t.feature);
	const double max_var = params_.held_anchor_max_sd_m * params_.held_anchor_max_sd_m;
	for (std::size_t k = 0; k < local_.order().size(); ++k)
	{
		const LandmarkId id = local_.order()[k];
		if (in_scan.count(id) || !map_->supported(id)) continue;
		const LocalSlam::FeaturePrediction held = local_.predictHeldFeature(k, scan.sensor_on_robot);
		RangeBearing virtual_measurement;
		virtual_measurement.range_m = held.z(0);
		virtual_measurement.bearing_rad = held.z(1);
		virtual_measurement.cov = held.covariance;
		const double range2 = virtual_measurement.range_m * virtual_measurement.range_m;
		if (std::max(virtual_measurement.cov(0, 0), range2 * virtual_measurement.cov(1, 1)) > max_var) continue;
		anchors.push_back({virtual_measurement, id});
	}
}

StepReport Dslam::associateByIds(const StepInput& step) const
{
	StepReport report;
	std::unordered_set<LandmarkId> seen;
	const auto& ms = step.scan->measurements;
	for (std::size_t i = 0; i < ms.size(); ++i)
	{
		if (!ms[i].id)
			throw InputError("step " + std::to_string(step.index) + ", measurement " + std::to_string(i) +
							 ": no landmark ID but [dslam] association = known_ids");
		const LandmarkId id = *ms[i].id;
		// A second measurement of one feature in one scan is not independent: use the first.
		if (!seen.insert(id).second)
			report.associations.push_back({Association::Kind::Rejected, id});
		else
			report.associations.push_back({map_->contains(id) ? Association::Kind::Matched : Association::Kind::New, id});
	}
	return report;
}

void Dslam::holdFirstSightings(const StepInput& step, StepReport& report)
{
	const Pose2 sensor = step.scan->sensor_on_robot;
	for (std::size_t i = 0; i < report.associations.size(); ++i)
	{
		auto& a = report.associations[i];
		if (a.kind != Association::Kind::New || (a.id >= 0 && local_.holds(a.id))) continue;
		const auto& m = step.scan->measurements[i];
		const LandmarkFromMeasurement p = landmarkFromRangeBearing(local_.robot(), sensor, m.range_m, m.bearing_rad);
		Eigen::Matrix2d cov = p.d_robot * local_.robotCov() * p.d_robot.transpose() +
			p.d_measurement * m.cov * p.d_measurement.transpose();
		cov = 0.5 * (cov + cov.transpose()).eval();
		const std::optional<LandmarkId> id = a.id >= 0 ? std::optional<LandmarkId>(a.id) : std::nullopt;
		if (confirmation_->confirm(id, p.position, cov, step.index)) continue;
		a = {Association::Kind::Rejected, a.id};
		++tally_.unconfirmed_sightings;
	}
}

void Dslam::nameNewFeatures(StepReport& report)
{
	for (auto& a : report.associations)
	{
		if (a.kind != Association::Kind::New) continue;
		if (a.id < 0)
		{
			while (started_.count(next_own_id_)) ++next_own_id_;
			a.id = next_own_id_++;
		}
		started_.insert(a.id);
	}
}

void Dslam::rejectOutliers(const Scan& scan, StepReport& report)
{
	const Pose2 sensor = scan.sensor_on_robot;
	const auto reject = [&](std::size_t i)
	{ report.associations[i] = {Association::Kind::Rejected, report.associations[i].id}; };

	// Localisation: against the local SLAM, before its update (step B).
	std::vector<IdentifiedMeasurement> used;
	std::vector<std::size_t> where;
	for (std::size_t i = 0; i < report.associations.size(); ++i)
		if (report.associations[i].kind != Association::Kind::Rejected)
		{
			const auto& m = scan.measurements[i];
			used.push_back({report.associations[i].id, Eigen::Vector2d(m.range_m, m.bearing_rad), m.cov});
			where.push_back(i);
		}
	for (int k : localOutliers(local_, used, sensor, params_.outlier_chi2_quantile))
	{
		reject(where[k]);
		++tally_.local_gate_rejections;
	}
	rejectReobservationOutliers(scan, report);

	// Mapping: the scan's mapped features jointly against Map(k), eq. (3.43)-(3.45).
	std::vector<LandmarkId> ids;
	std::vector<std::size_t> index;
	for (std::size_t i = 0; i < report.associations.size(); ++i)
	{
		const auto& a = report.associations[i];
		if (a.kind == Association::Kind::Matched && map_->supported(a.id))
		{
			ids.push_back(a.id);
			index.push_back(i);
		}
	}
	if (ids.size() < 2) return;
	Eigen::VectorXd z(2 * ids.size());
	Eigen::MatrixXd R = Eigen::MatrixXd::Zero(z.size(), z.size());
	MappedView view;
	view.map_xy.resize(z.size());
	for (std::size_t k = 0; k < ids.size(); ++k)
	{
		const auto& m = scan.measurements[index[k]];
		z.segment<2>(2 * k) << m.range_m, m.bearing_rad;
		R.block<2, 2>(2 * k, 2 * k) = m.cov;
		view.map_xy.segment<2>(2 * k) = map_->position(ids[k]);
	}
	view.measured = pointsInRobotFrame(z, R, sensor);
	view.map_cov = map_->covariance(ids);
	for (int k : mappedOutliers(view, params_.outlier_chi2_quantile))
	{
		reject(index[k]);
		++tally_.map_gate_rejections;
	}
}

void Dslam::rejectReobservationOutliers(const Scan& scan, StepReport& report)
{
	const Pose2 sensor = scan.sensor_on_robot;
	const double gate = chi2GateBound(params_.id_gate_chi2_quantile, 2);
	if (std::isinf(gate)) return;
	for (std::size_t i = 0; i < report.associations.size(); ++i)
	{
		auto& a = report.associations[i];
		if (a.kind != Association::Kind::Matched || local_.holds(a.id) || !map_->supported(a.id)) continue;
		const auto& m = scan.measurements[i];
		const double d2 = reobservationDistance2(local_.robot(), local_.robotCov(), sensor, map_->position(a.id),
												 map_->covariance({a.id}), {a.id, {m.range_m, m.bearing_rad}, m.cov});
		if (d2 <= gate) continue;
		a = {Association::Kind::Rejected, a.id};
		++tally_.reobservation_gate_rejections;
	}
}

Dslam::Observed Dslam::observed(const Scan& scan, const StepReport& report) const
{
	Observed obs;
	Eigen::VectorXd z(2 * scan.measurements.size());
	Eigen::MatrixXd R = Eigen::MatrixXd::Zero(z.size(), z.size());
	int n = 0;
	for (std::size_t i = 0; i < report.associations.size(); ++i)
	{
		const auto& a = report.associations[i];
		if (a.kind == Association::Kind::Rejected) continue;
		const auto& m = scan.measurements[i];
		if (a.kind == Association::Kind::Matched) obs.mapped.push_back(n);
		obs.all.push_back({a.id, Eigen::Vector2d(m.range_m, m.bearing_rad), m.cov});
		z.segment<2>(2 * n) = obs.all.back().z;
		R.block<2, 2>(2 * n, 2 * n) = m.cov;
		++n;
	}
	obs.points = pointsInRobotFrame(z.head(2 * n), R.topLeftCorner(2 * n, 2 * n), scan.sensor_on_robot);

	std::vector<ReferenceCandidate> candidates;
	for (int i : obs.mapped) candidates.push_back({obs.points.point(i), map_->mappedOrder(obs.all[i].id)});
	const bool anchoring = chain_.rootIsMapFrame() && chain_.scans() < params_.anchor_scans;
	if (anchoring) return obs;	// no pair: combined into the anchor
	if (const auto p = chooseReferencePair(candidates, params_.referenceRules()))
		obs.pair = std::make_pair(obs.mapped[p->first], obs.mapped[p->second]);
	return obs;
}

void Dslam::localize(const Observed& obs, const Pose2& sensor)
{
	// B -> C: features of Map(k) in view, and any the local SLAM holds.
	std::vector<IdentifiedMeasurement> known, fresh;
	for (std::size_t i = 0; i < obs.all.size(); ++i)
		(map_->contains(obs.all[i].id) || local_.holds(obs.all[i].id) ? known : fresh).push_back(obs.all[i]);
	local_.observe(known, sensor);
	if (obs.pair) fuseWithKidnappedRobot(obs, sensor);	// F -> G, then C, G -> D
	local_.addFeatures(fresh, sensor);					// D -> E
}

void Dslam::fuseWithKidnappedRobot(const Observed& obs, const Pose2& sensor)
{
	// Both states list the robot, then f1, f2 and the other mapped features in view.
	const std::vector<int> order = [&] {
		std::vector<int> o = {obs.pair->first, obs.pair->second};
		for (int i : obs.mapped)
			if (i != obs.pair->first && i != obs.pair->second) o.push_back(i);
		return o;
	}();
	KidnappedInput in;
	std::vector<LandmarkId> ids;
	for (int i : order)
	{
		ids.push_back(obs.all[i].id);
		in.z_loc.push_back(obs.all[i]);
	}
	in.features.resize(2 * ids.size());
	for (std::size_t k = 0; k < ids.size(); ++k) in.features.segment<2>(2 * k) = map_->position(ids[k]);
	in.features_cov = map_->covariance(ids);
	in.sensor_on_robot = sensor;
	in.iterations = params_.kidnapped_iterations;
	const Eigen::Vector3d z_rob = robotRelativeToPair(obs.points.point(order[0]), obs.points.point(order[1]));
	in.initial_robot = robotFromPair(in.features.segment<2>(0), in.features.segment<2>(2), z_rob);

	local_.bringToFront(ids);  // features held out of view (local_hold_steps) stay behind them
	std::optional<GaussianState> from_map;
	try
	{
		from_map = solveKidnappedRobot(in);
	}
	catch (const NumericalError&)
	{
		++tally_.ci_failures;  // degenerate geometry: keep the local SLAM estimate (step D = C)
		return;
	}
	const GaussianState local{local_.state(), local_.covariance()};
	const Eigen::Index in_view = from_map->mean.size();
	const bool agree = params_.fusion_gate_chi2_quantile >= 1 ||
		robotEstimatesAgree(robotMarginal(local), robotMarginal(*from_map));
	guard_.fusion(agree);
	if (!agree)
	{
		++tally_.ci_disagreements;	// a wrong match or a poorly known pair: keep the local estimate ...
		if (relocalisationDue(in, *from_map))
		{
			local_.arrange(ids);  // ... unless the local SLAM is the one lost: what it held out of view goes too
			local_.setState(from_map->mean, from_map->cov);
			++tally_.relocalisations;
		}
		return;
	}
	try
	{
		CiResult ci;
		if (params_.fusion == FusionScope::Robot)
		{
			// CI of the robot marginals; the local features follow through
			// their conditional on the robot (see DslamParams::fusion).
			ci = covarianceIntersection(robotMarginal(local), robotMarginal(*from_map));
			ci.fused = withLeadingMarginal(local, ci.fused);
		}
		else
		{
			// Eq. (3.20)-(3.21) over [X_r, X_1..X_m1]; features held out of view follow.
			ci = covarianceIntersection(leadingMarginal(local, in_view), *from_map);
			ci.fused = withLeadingMarginal(local, ci.fused);
		}
		local_.setState(ci.fused.mean, ci.fused.cov);
		++tally_.ci_fusions;
		tally_.omega_sum += ci.omega;
	}
	catch (const NumericalError&)
	{
		++tally_.ci_failures;
	}
}

bool Dslam::relocalisationDue(const KidnappedInput& in, const GaussianState& from_map) const
{
	// Without IDs a run of disagreements is as likely a wrong association
	// (the map's estimate then fits its wrong pairs): on long_gap, relocalising
	// there turned every detected divergence into a silent 18 m error.
	const int due = params_.relocalise_after_disagreeing_scans;
	if (!associated_by_ids_ || due <= 0 || guard_.disagreeingInARow() < due) return false;
	const int dof = kidnappedFitDof(in);
	return dof > 0 && kidnappedFitChi2(in, from_map) <= chi2GateBound(params_.fusion_gate_chi2_quantile, dof);
}

bool Dslam::robotEstimatesAgree(const GaussianState& local, const GaussianState& from_map) const
{
	// Covariance intersection fuses any two estimates, even contradictory
	// ones (eq. 3.20-3.21). Two estimates of one pose must agree within their
	// combined uncertainty; the sum of the covariances bounds that of the
	// difference for any correlation up to a factor 2, taken here as the
	// outlier gate's quantile on 3 dof.
	Eigen::Vector3d d = local.mean.head<3>() - from_map.mean.head<3>();
	d(2) = wrapAngle(d(2));
	const Eigen::Matrix3d S = 2.0 * (local.cov.topLeftCorner<3, 3>() + from_map.cov.topLeftCorner<3, 3>());
	const Eigen::LDLT<Eigen::Matrix3d> ldlt(S);
	return ldlt.info() == Eigen::Success && d.dot(ldlt.solve(d)) <= chi2GateBound(params_.fusion_gate_chi2_quantile, 3);
}

MapUpdate Dslam::updateFromPair(const std::vector<LandmarkId>& ids, const PointSet& points, std::pair<int, int> pair)
{
	const auto order = pairFirst(static_cast<int>(ids.size()), pair.first, pair.second);
	std::vector<LandmarkId> ordered_ids;
	for (int i : order) ordered_ids.push_back(ids[i]);
	return map_->updateRelative(ordered_ids, selectPoints(points, order));
}

void Dslam::updateMap(const Observed& obs, const Pose2& sensor)
{
	if (obs.pair)
	{
		// Admissible: z_map of this scan, eq. (3.12)-(3.15); a new chain starts here.
		std::vector<LandmarkId> ids;
		for (const auto& m : obs.all) ids.push_back(m.id);
		pending_ = updateFromPair(ids, obs.points, *obs.pair);
		chain_.restart(obs.all, sensor);
		++tally_.admissible;
		return;
	}
	++tally_.inadmissible;
	chain_.absorb(obs.all, sensor);
	if (pending_)
	{
		map_->withdraw(*pending_);
		++tally_.withdrawals;
	}
	if (chain_.rootIsMapFrame())
	{
		pending_ = map_->updateAnchor(chain_.ids(), chain_.features());
		++tally_.anchor_updates;
	}
	else
		applyVirtualObservation(sensor);
}

void Dslam::applyVirtualObservation(const Pose2& sensor)
{
	// Sec. 3.4.1: the chain's estimate as ranges and bearings from here.
	const VirtualObservation v = chain_.virtualObservation(sensor);
	const PointSet points = pointsInRobotFrame(v.range_bearing, v.cov, sensor);
	std::vector<ReferenceCandidate> candidates;
	std::vector<int> index;
	for (std::size_t i = 0; i < v.ids.size(); ++i)
		if (map_->supported(v.ids[i]))
		{
			candidates.push_back({points.point(static_cast<int>(i)), map_->mappedOrder(v.ids[i])});
			index.push_back(static_cast<int>(i));
		}
	ReferenceRules rules = params_.referenceRules();
	auto pair = chooseReferencePair(candidates, rules);
	if (!pair) pair = chooseReferencePair(candidates, {rules.policy, 0.0, 0.0});
	if (!pair)
		throw NumericalError("D-SLAM: the virtual observation holds fewer than two distinct mapped features");
	pending_ = updateFromPair(v.ids, points, {index[pair->first], index[pair->second]});
	++tally_.virtual_updates;
}

PoseEstimate Dslam::robotPose() const { return {local_.robot(), local_.robotCov()}; }

Estimate Dslam::estimate() const
{
	Estimate e;
	e.robot = robotPose();
	if (map_) e.landmarks = map_->landmarks();
	return e;
}

CostFigures Dslam::costFigures() const
{
	CostFigures c;
	if (!map_) return c;
	const SparseCounters sc = map_->core().counters();
	c.state_dim = static_cast<std::size_t>(map_->core().stateDim());
	c.info_nnz = sc.information_nnz;
	c.poses_in_state = 0;  // the map state holds features only (Sec. 3.1.3)
	c.counters = sc.list();
	const auto add = [&](const char* name, double v) { c.counters.emplace_back(name, v); };
	add("admissible_scans", static_cast<double>(tally_.admissible));
	add("inadmissible_scans", static_cast<double>(tally_.inadmissible));
	add("map_withdrawals", static_cast<double>(tally_.withdrawals));
	add("virtual_updates", static_cast<double>(tally_.virtual_updates));
	add("anchor_updates", static_cast<double>(tally_.anchor_updates));
	add("ci_fusions", static_cast<double>(tally_.ci_fusions));
	add("ci_failures", static_cast<double>(tally_.ci_failures));
	add("ci_disagreements", static_cast<double>(tally_.ci_disagreements));
	add("local_gate_rejections", static_cast<double>(tally_.local_gate_rejections));
	add("map_gate_rejections", static_cast<double>(tally_.map_gate_rejections));
	add("reobservation_gate_rejections", static_cast<double>(tally_.reobservation_gate_rejections));
	add("unconfirmed_sightings", static_cast<double>(tally_.unconfirmed_sightings));
	add("tracked_matches", static_cast<double>(tally_.tracked_matches));
	add("relinearisations", static_cast<double>(tally_.relinearisations));
	add("relinearised_terms", static_cast<double>(tally_.relinearised_terms));
	add("corrections_relinearised", static_cast<double>(tally_.corrections_relinearised));
	add("relinearisations_rejected", static_cast<double>(map_->rejectedPasses()));
	add("relocalisations", static_cast<double>(tally_.relocalisations));
	add("ci_omega_mean", tally_.ci_fusions ? tally_.omega_sum / static_cast<double>(tally_.ci_fusions) : 0.0);
	if (association_)
	{
		add("jcbb_nodes", static_cast<double>(association_->jcbbNodes()));
		add("jcbb_fallbacks", static_cast<double>(association_->jcbbFallbacks()));
		add("relative_test_drops", static_cast<double>(association_->droppedByRelativeTest()));
		add("anchor_conflicts", static_cast<double>(association_->anchorConflicts()));
	}
	return c;
}

std::optional<InformationPattern> Dslam::informationPattern() const
{
	if (!map_ || map_->featureCount() == 0) return std::nullopt;
	return map_->core().pattern();
}

std::optional<StateInformation> Dslam::stateInformation() const
{
	if (!map_ || map_->featureCount() == 0) return std::nullopt;
	return map_->stateInformation();  // features only (eq. 3.10)
}

}  // namespace esif
