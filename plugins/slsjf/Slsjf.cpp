#include "Slsjf.h"

#include "VirtualObservation.h"

#include <esif/core/Elapsed.h>
#include <esif/core/Errors.h>

#include <chrono>
#include <set>

IMPLEMENTS_MRPT_OBJECT(Slsjf, FilterPlugin, esif)

namespace esif
{
using namespace slsjf;

namespace
{
using Clock = SteadyClock;
}  // namespace

void Slsjf::start()
{
	global_ = std::make_unique<GlobalMap>(params_.recovery, params_.jacobians);
}

void Slsjf::requireConfigured() const
{
	if (!global_) throw std::logic_error("Slsjf: used before configure()");
}

void Slsjf::finishJoining()
{
	requireConfigured();
	if (params_.smoothing != Smoothing::None && !records_.empty()) smooth();
	marginals();
}

bool Slsjf::useIds(const LocalMap& map) const
{
	switch (params_.association)
	{
		case MapAssociationMethod::KnownIds: return true;
		case MapAssociationMethod::Auto:
			return (map.ids_identify_features && !sawMeasurementWithoutId()) || localFeaturesCarryGlobalIds();
		default: return localFeaturesCarryGlobalIds();
	}
}

MapAssociationOutcome Slsjf::associate(const LocalMap& map, std::optional<VarId> start)
{
	const Eigen::MatrixXd local_cov = map.covarianceMatrix();  // a copy, or the inverse of a file's information
	if (!useIds(map)) return associateGeometrically(map, local_cov, start, *global_, params_);
	MapAssociationOutcome out = associateByIds(map, local_cov, start, *global_, params_);
	if (localFeaturesCarryGlobalIds() && start)
		associateUnidentifiedGeometrically(map, local_cov, *start, *global_, params_, out);
	return out;
}

void Slsjf::fuseLocalMap(const LocalMap& map)
{
	requireConfigured();
	const auto t0 = Clock::now();
	const std::optional<VarId> start = global_->startPose(map);	 // Algorithm 5.1, step 1
	const auto t_association = Clock::now();
	MapAssociationOutcome outcome = associate(map, start);	// step 2
	const double association_s = secondsSince(t_association);
	global_->fuse(map, start, outcome.decisions, outcome.extent);  // steps 3-5
	last_end_cov_ = global_->covariance({global_->fusedMaps().back().end});
	marginals_.reset();

	MapRecord record{map.first_step, map.step_reports, {}, outcome.decisions};
	for (const auto& f : map.features) record.local_ids.push_back(f.id);
	records_.push_back(std::move(record));
	outcome.tally.seconds = association_s;
	outcome.tally.features_rejected = rejectedCount(outcome.decisions);
	tally_.association += outcome.tally;
	tally_.maps_selected += outcome.maps_selected;

	if (params_.smoothing == Smoothing::EveryKMaps &&
		records_.size() % static_cast<std::size_t>(params_.smoothing_every_maps) == 0)
		smooth();
	costs_.push_back({map.index, secondsSince(t0), association_s, static_cast<std::size_t>(global_->core().stateDim())});
}

std::optional<EarlierFeatures> Slsjf::globalFeaturesNearOpenMapStart(double radius_m)
{
	requireConfigured();
	if (records_.empty()) return EarlierFeatures{};
	global_->core().refresh();	// the estimates as of this fusion, as the covariance recovery sees them
	const VarId end = global_->fusedMaps().back().end;
	const Pose2 frame = global_->pose(end);
	std::vector<VarId> vars = {end};
	std::vector<LandmarkId> ids;
	std::vector<Eigen::Vector2d> points;
	for (const VarId v : global_->featureVars())
		if ((global_->point(v) - frame.head<2>()).norm() <= radius_m)
		{
			vars.push_back(v);
			ids.push_back(global_->featureId(v));
			points.push_back(global_->point(v));
		}
	return earlierFeaturesInFrame(frame, ids, points, global_->covariance(vars));
}

void Slsjf::smooth()
{
	const auto t0 = Clock::now();
	tally_.smoothing_iterations += global_->relinearise(params_.smoothing_max_iterations, params_.smoothing_tolerance);
	++tally_.smoothing_runs;
	last_end_cov_ = global_->covariance({global_->fusedMaps().back().end});
	marginals_.reset();
	tally_.smoothing_s += secondsSince(t0);
}

const std::vector<Eigen::MatrixXd>& Slsjf::marginals() const
{
	if (!marginals_) marginals_ = global_->core().stateDim() > 0 ? global_->marginals() : std::vector<Eigen::MatrixXd>{};
	return *marginals_;
}

PoseEstimate Slsjf::openMapStart() const
{
	if (records_.empty()) return {};
	const Pose2 end = global_->pose(global_->fusedMaps().back().end);
	if (const auto& link = builder().openMapLink())
		return composeIndependent({end, last_end_cov_}, {link->delta, link->cov});
	return {end, last_end_cov_};
}

PoseEstimate Slsjf::robotPose() const
{
	requireConfigured();
	// The global pose of the open map's start composed with the robot pose
	// in the open map: two independent estimates.
	const PoseEstimate start = openMapStart();
	const PoseEstimate local = builder().openMap().robotPose();
	return composeIndependent(start, local);
}

Estimate Slsjf::estimate() const
{
	requireConfigured();
	Estimate e;
	e.robot = robotPose();
	const auto& P = marginals();
	std::set<LandmarkId> global_ids;
	for (const VarId v : global_->featureVars())
	{
		e.landmarks.push_back({global_->featureId(v), global_->point(v), P[v.value]});
		global_ids.insert(global_->featureId(v));
	}
	// Features of the open map not yet in the global map, placed through the open map's start pose.
	const PoseEstimate start = openMapStart();
	const Pose2 s = start.mean;
	const auto& open = builder().openMap();
	for (std::size_t i = 0; i < open.ids().size(); ++i)
	{
		if (global_ids.count(open.ids()[i])) continue;
		const Eigen::Vector2d p = open.core().landmark(i);
		const auto J = composeJacobians(s, Pose2(p.x(), p.y(), 0));
		const Eigen::Matrix2d cov = (J.d_a * start.cov * J.d_a.transpose()).topLeftCorner<2, 2>() +
			J.d_b.topLeftCorner<2, 2>() * open.core().landmarkCov(i) * J.d_b.topLeftCorner<2, 2>().transpose();
		e.landmarks.push_back({open.ids()[i], transformPoint(s, p), 0.5 * (cov + cov.transpose())});
	}
	return e;
}

std::vector<PoseEstimate> Slsjf::endPoses() const
{
	requireConfigured();
	const auto& P = marginals();
	std::vector<PoseEstimate> out;
	for (const auto& fused : global_->fusedMaps())
	{
		Pose2 x = global_->pose(fused.end);
		x(2) = wrapAngle(x(2));
		out.push_back({x, P[fused.end.value]});
	}
	return out;
}

StepReport Slsjf::mapReport(std::size_t k) const
{
	if (k == 0 || k > records_.size()) return {};
	return records_[k - 1].decisions;
}

std::vector<MapJoiningPlugin::SettledFusion> Slsjf::settledFusions() const
{
	std::vector<SettledFusion> out;
	for (const auto& record : records_) out.push_back({record.step_reports, record.local_ids, record.decisions});
	return out;
}

std::optional<std::vector<PoseEstimate>> Slsjf::smoothedTrajectory() const
{
	const std::vector<PoseEstimate>& poses = localPoses();
	if (params_.smoothing == Smoothing::None || poses.empty()) return std::nullopt;
	const auto& P = marginals();
	std::vector<PoseEstimate> out;
	out.reserve(poses.size());
	for (std::size_t k = 0; k < records_.size(); ++k)
	{
		const auto& start = global_->fusedMaps()[k].start;
		const PoseEstimate s{
			global_->startEstimate(start),
			start ? Eigen::Matrix3d(P[start->value]) : Eigen::Matrix3d::Zero()};
		const std::size_t first = records_[k].first_step, last = first + records_[k].step_reports.size() - 1;
		for (std::size_t i = first; i < last && i < poses.size(); ++i)
			out.push_back(composeIndependent(s, poses[i]));
		// The map's last step is its end pose, a variable of the global state.
		const VarId end = global_->fusedMaps()[k].end;
		Pose2 e = global_->pose(end);
		e(2) = wrapAngle(e(2));
		out.push_back({e, P[end.value]});
	}
	return out;
}

SparseInformationCore& Slsjf::globalInformation() const
{
	requireConfigured();
	return global_->core();
}

std::optional<StateInformation> Slsjf::stateInformation() const
{
	requireConfigured();
	if (global_->fusedMaps().empty()) return std::nullopt;
	return global_->stateInformation();
}

CostFigures Slsjf::costFigures() const
{
	requireConfigured();
	CostFigures c;
	const SparseCounters sparse = global_->counters();
	c.state_dim = static_cast<std::size_t>(global_->core().stateDim());
	c.poses_in_state = global_->poseCount();
	c.info_nnz = sparse.information_nnz;
	c.counters = sparse.list();
	c.counters.emplace_back("local_maps_fused", static_cast<double>(records_.size()));
	tally_.association.appendCounters(c.counters);
	c.counters.emplace_back("association_maps_selected", static_cast<double>(tally_.maps_selected));
	c.counters.emplace_back("smoothing_runs", static_cast<double>(tally_.smoothing_runs));
	c.counters.emplace_back("smoothing_iterations", static_cast<double>(tally_.smoothing_iterations));
	c.counters.emplace_back("smoothing_s", tally_.smoothing_s);
	appendLocalMapCounters(c.counters);
	return c;
}

}  // namespace esif
