#include <esif/core/Errors.h>
#include <esif/localmap/LocalMapBuilder.h>
#include "localmap/PreviousMapMatcher.h"
#include <esif/core/MeasurementSubset.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

namespace esif
{
namespace
{
/// Whether LandmarkEkf associates `scan` by its landmark IDs (a new feature
/// then keeps its measured ID) rather than by distance (it then numbers the
/// feature itself, whether or not the measurement carries an ID): the rule
/// of LandmarkEkf::associateScan.
bool associatedByIds(const EkfAssociationParams& params, const Scan& scan)
{
	switch (params.association)
	{
		case EkfAssociation::KnownIds: return true;
		case EkfAssociation::Auto:
			return std::all_of(scan.measurements.begin(), scan.measurements.end(),
							   [](const RangeBearing& m) { return m.id.has_value(); });
		default: return false;
	}
}
}  // namespace

LocalMapBuilder::LocalMapBuilder(const LocalMapBuilderParams& params)
	: params_(params), ekf_(params.association, kFirstOwnId)
{
}

StepReport LocalMapBuilder::processStep(const StepInput& step)
{
	if (steps_ == 0) first_step_ = step.index;
	StepInput in_map = step;
	if (link_pending_ && step.odometry)
	{
		// Eq. (5.4): this step's motion links the previous end pose to the
		// new map's start pose, which is the origin of the new map.
		link_ = step.odometry;
		link_pending_ = false;
		in_map.odometry.reset();
		if (earlier_through_link_) startAssociationFilter(earlier_through_link_->inFrame(link_->delta, link_->cov));
		earlier_through_link_.reset();
	}
	else
	{
		link_pending_ = false;
		if (step.odometry) travelled_m_ += std::hypot(step.odometry->delta.x(), step.odometry->delta.y());
	}
	const StepReport report = association_ekf_ ? processAsTheGlobalMapDecides(in_map) : ekf_.processStep(in_map);
	// Features the filter numbered itself: every new one of a scan associated
	// by distance, even when the log's IDs are present (association = nn|jcbb).
	if (step.scan && !associatedByIds(params_.association, *step.scan))
		for (const auto& a : report.associations)
			if (a.kind == Association::Kind::New && !earlier_ids_.count(a.id)) own_ids_.insert(a.id);
	next_own_id_ = std::max(next_own_id_, ekf_.nextOwnId());
	if (association_ekf_) next_own_id_ = std::max(next_own_id_, association_ekf_->nextOwnId());
	reports_.push_back(report);
	++steps_;
	last_step_ = step.index;
	measurements_ += step.scan ? step.scan->measurements.size() : 0;
	if (policyWantsToClose()) closed_ = closeOpenMap();
	return report;
}

StepReport LocalMapBuilder::processAsTheGlobalMapDecides(const StepInput& step)
{
	const StepReport decided = association_ekf_->processStep(step);
	if (!step.scan) return ekf_.processStep(step);
	// The open map takes the decided measurements under the decided IDs and
	// leaves out the rest, as the association filter did.
	MeasurementSubset decided_part = measurementSubset(*step.scan, [&](std::size_t i, const RangeBearing&) {
		return decided.associations[i].kind != Association::Kind::Rejected;
	});
	for (std::size_t u = 0; u < decided_part.kept.size(); ++u)
		decided_part.scan.measurements[u].id = decided.associations[decided_part.kept[u]].id;
	StepInput by_id = step;
	by_id.scan = decided_part.scan;
	const StepReport in_map = ekf_.processStep(by_id);
	for (const Association& a : in_map.associations)
		earlier_starts_ += a.kind == Association::Kind::New && earlier_ids_.count(a.id);
	return decided_part.spread(in_map);
}

void LocalMapBuilder::setEarlierFeatures(EarlierFeatures features)
{
	if (steps_ > 0) throw std::logic_error("LocalMapBuilder::setEarlierFeatures: the open map has taken steps");
	if (link_pending_)
		earlier_through_link_ = std::move(features);
	else
		startAssociationFilter(features);
}

void LocalMapBuilder::startAssociationFilter(const EarlierFeatures& features)
{
	earlier_ids_ = std::set<LandmarkId>(features.ids.begin(), features.ids.end());
	association_ekf_.emplace(params_.association, next_own_id_, params_.jacobians);
	association_ekf_->addPriorLandmarks(features);
	EkfAssociationParams by_ids = params_.association;
	by_ids.association = EkfAssociation::KnownIds;
	ekf_ = LandmarkEkf(by_ids, next_own_id_, params_.jacobians);
}

void LocalMapBuilder::reserveIdsUpTo(LandmarkId largest_input_id)
{
	next_own_id_ = std::max(next_own_id_, largest_input_id + 1);
	ekf_.reserveIdsUpTo(largest_input_id);
}

std::optional<LocalMap> LocalMapBuilder::takeClosedMap()
{
	std::optional<LocalMap> out;
	out.swap(closed_);
	return out;
}

std::optional<LocalMap> LocalMapBuilder::finish()
{
	if (steps_ == 0) return std::nullopt;
	return closeOpenMap();
}

bool LocalMapBuilder::policyWantsToClose() const
{
	const bool steps = params_.local_map_steps > 0 && steps_ >= static_cast<std::size_t>(params_.local_map_steps);
	const bool features = params_.local_map_max_features > 0 &&
		ekf_.core().landmarkCount() >= static_cast<std::size_t>(params_.local_map_max_features);
	const bool distance = params_.local_map_max_distance_m > 0 && travelled_m_ >= params_.local_map_max_distance_m;
	if (!(steps || features || distance)) return false;
	return !previous_ || openMapCommonFeatures() >= static_cast<std::size_t>(params_.local_map_min_common_features);
}

std::size_t LocalMapBuilder::openMapCommonFeatures() const
{
	if (!previous_) return 0;
	std::set<LandmarkId> previous_ids;
	for (const auto& f : previous_->features) previous_ids.insert(f.id);
	const std::set<LandmarkId>& counted_in =
		params_.local_map_common_features_in == CommonFeaturesIn::EarlierMaps ? ids_in_closed_maps_ : previous_ids;
	std::size_t common = 0;
	for (const LandmarkId id : ekf_.ids()) common += !own_ids_.count(id) && counted_in.count(id);
	if (own_ids_.empty()) return common;
	if (params_.local_map_common_features_in == CommonFeaturesIn::EarlierMaps && own_in_global_)
		if (const auto in_global = own_in_global_(ekf_, own_ids_)) return common + *in_global;
	for (const auto& m : matchOwnFeaturesToPrevious()) common += m.has_value();
	return common;
}

std::vector<std::optional<std::size_t>> LocalMapBuilder::matchOwnFeaturesToPrevious() const
{
	std::vector<std::size_t> own;
	for (std::size_t i = 0; i < ekf_.ids().size(); ++i)
		if (own_ids_.count(ekf_.ids()[i])) own.push_back(i);
	if (!previous_ || own.empty()) return std::vector<std::optional<std::size_t>>(own.size());
	OpenMapFeatures open;
	open.positions.resize(static_cast<Eigen::Index>(own.size()), 2);
	std::vector<Eigen::Index> rows;
	for (std::size_t a = 0; a < own.size(); ++a)
	{
		open.positions.row(a) = ekf_.core().landmark(own[a]).transpose();
		rows.push_back(static_cast<Eigen::Index>(3 + 2 * own[a]));
		rows.push_back(static_cast<Eigen::Index>(4 + 2 * own[a]));
	}
	open.covariance = ekf_.core().covariance()(rows, rows);
	const auto method = params_.association.association == EkfAssociation::NearestNeighbor
		? AssociationMethod::NearestNeighbor
		: AssociationMethod::Jcbb;
	return matchPreviousMap(*previous_, link_, open, method, params_.association.gate_chi2_quantile);
}

namespace
{
/// The authors' stabilisation of near-zero robot variances, applied to the
/// covariance itself so that the map's covariance and information describe
/// one Gaussian (and the covariance of a map in which the robot did not
/// move, whose robot block is zero, is positive definite).
Eigen::MatrixXd stabilised(Eigen::MatrixXd P)
{
	for (int r = 0; r < 3; ++r)
		if (P(r, r) < LocalMapBuilder::kMinRobotVariance) P(r, r) += LocalMapBuilder::kMinRobotVariance;
	return P;
}

/// Information matrix of a (stabilised) local-map covariance.
Eigen::MatrixXd informationOf(const Eigen::MatrixXd& P, std::size_t map_index)
{
	const Eigen::LLT<Eigen::MatrixXd> llt(P);
	if (llt.info() != Eigen::Success)
		throw NumericalError("local map " + std::to_string(map_index) + ": covariance is not positive definite");
	Eigen::MatrixXd I = llt.solve(Eigen::MatrixXd::Identity(P.rows(), P.cols()));
	return 0.5 * (I + I.transpose());
}

/// Gives up every rename onto an ID the open map holds already, or that
/// another rename takes, until no ID is held twice: in a log whose scans
/// carry IDs only in part, a landmark seen by the builder's numbers in one
/// scan and by its ID in another is two features of the open map, and the
/// numbered one keeps its number.
void keepEveryIdOnce(const std::vector<LandmarkId>& ids, std::map<LandmarkId, LandmarkId>& renames)
{
	for (bool changed = true; changed;)
	{
		changed = false;
		std::set<LandmarkId> held;	// IDs of the features not renamed
		for (const LandmarkId id : ids)
			if (!renames.count(id)) held.insert(id);
		std::set<LandmarkId> taken;
		for (auto it = renames.begin(); it != renames.end();)
			if (held.count(it->second) || !taken.insert(it->second).second)
				it = renames.erase(it), changed = true;
			else
				++it;
	}
}

void renameInReports(std::vector<StepReport>& reports, const std::map<LandmarkId, LandmarkId>& renames)
{
	for (auto& r : reports)
		for (auto& a : r.associations)
			if (const auto it = renames.find(a.id); it != renames.end() && a.kind != Association::Kind::Rejected)
				a.id = it->second;
}
}  // namespace

LocalMap LocalMapBuilder::closeOpenMap()
{
	LocalMap map;
	map.index = index_;
	map.end_pose = ekf_.core().robot();
	map.covariance = stabilised(ekf_.core().covariance());
	map.information = informationOf(*map.covariance, index_);
	map.link = link_;
	map.first_step = first_step_;
	map.last_step = last_step_;
	map.steps = steps_;
	map.measurements = measurements_;

	// Features the builder numbered that are features of the previous map take
	// that map's IDs; not when the association filter decided the scans (even
	// with no global feature in its radius): the filter's own numbers are then
	// features the global map did not give, left to the map level.
	std::map<LandmarkId, LandmarkId> renames;
	if (previous_ && !own_ids_.empty() && !association_ekf_)
	{
		std::size_t a = 0;
		const auto matches = matchOwnFeaturesToPrevious();
		for (const LandmarkId id : ekf_.ids())
			if (own_ids_.count(id))
			{
				if (const auto m = matches[a++]) renames[id] = previous_->features[*m].id;
			}
		keepEveryIdOnce(ekf_.ids(), renames);
	}
	for (std::size_t i = 0; i < ekf_.ids().size(); ++i)
	{
		const LandmarkId own = ekf_.ids()[i];
		const auto renamed = renames.find(own);
		const LandmarkId id = renamed != renames.end() ? renamed->second : own;
		const bool earlier = renamed != renames.end() || (!own_ids_.count(own) && ids_in_closed_maps_.count(own));
		map.features.push_back({id, ekf_.core().landmark(i), earlier});
	}
	renameInReports(reports_, renames);
	map.step_reports = std::move(reports_);
	map.validate("local-map builder");

	for (const auto& f : map.features) ids_in_closed_maps_.insert(f.id);
	previous_ = map;
	startNextMap();
	return map;
}

SightingRejections LocalMapBuilder::rejections() const
{
	SightingRejections all = rejections_in_closed_maps_;
	all += ekf_.rejections();
	if (association_ekf_) all += association_ekf_->rejections();
	return all;
}

void LocalMapBuilder::startNextMap()
{
	rejections_in_closed_maps_ += ekf_.rejections();
	if (association_ekf_) rejections_in_closed_maps_ += association_ekf_->rejections();
	association_ekf_.reset();
	earlier_ids_.clear();
	earlier_through_link_.reset();
	++index_;
	ekf_ = LandmarkEkf(params_.association, next_own_id_, params_.jacobians);
	steps_ = measurements_ = 0;
	travelled_m_ = 0;
	own_ids_.clear();
	reports_.clear();
	link_.reset();
	link_pending_ = params_.local_map_link == LocalMapLink::Odometry;
}

}  // namespace esif
