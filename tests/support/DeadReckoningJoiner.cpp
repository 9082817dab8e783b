#include "DeadReckoningJoiner.h"

#include <esif/core/Elapsed.h>
#include <esif/core/Errors.h>
#include <esif/models/Se2.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>

IMPLEMENTS_MRPT_OBJECT(DeadReckoningJoiner, FilterPlugin, esif::test)

namespace esif::test
{
namespace
{
using Clock = SteadyClock;

/// `a` (+) `b` with first-order covariance, a and b independent.
PoseEstimate composeEstimates(const PoseEstimate& a, const Pose2& b, const Eigen::Matrix3d& b_cov)
{
	const Pose2 pa = a.mean;
	const ComposeJacobians J = composeJacobians(pa, b);
	PoseEstimate out;
	out.mean = compose(pa, b);
	out.cov = J.d_a * a.cov * J.d_a.transpose() + J.d_b * b_cov * J.d_b.transpose();
	return out;
}

/// The map's covariance: its own when built here, else the inverse of the information read from files.
Eigen::MatrixXd covarianceOf(const LocalMap& map)
{
	if (map.covariance) return *map.covariance;
	const Eigen::LLT<Eigen::MatrixXd> llt(map.information);
	if (llt.info() != Eigen::Success) throw NumericalError("information matrix is not positive definite");
	return llt.solve(Eigen::MatrixXd::Identity(map.information.rows(), map.information.cols()));
}
}  // namespace

void DeadReckoningJoinerParams::declare(ParamBinder& b)
{
	builder.declare(b);
	b.real("match_distance_m", match_distance_m,
		   "0: associate the maps' features by ID; > 0: to the nearest global landmark within this distance [m]",
		   Bounds::nonNegative());
}

void DeadReckoningJoiner::configure(const ConfigSection& section)
{
	loadParams(params_, section);
	builder_.emplace(params_.builder);
}

StepReport DeadReckoningJoiner::processStep(const StepInput& step)
{
	if (!builder_) builder_.emplace(params_.builder);
	const StepReport report = builder_->processStep(step);
	++steps_;
	if (auto map = builder_->takeClosedMap()) joinLocalMap(*map);
	return report;
}

void DeadReckoningJoiner::finish()
{
	if (builder_ && steps_ > 0)
		if (auto map = builder_->finish()) joinLocalMap(*map);
	finished_ = true;
}

PoseEstimate DeadReckoningJoiner::robotPose() const
{
	PoseEstimate start = end_poses_.empty() ? PoseEstimate{} : end_poses_.back();
	if (!builder_ || builder_->openMapSteps() == 0) return start;
	if (const auto& link = builder_->openMapLink()) start = composeEstimates(start, link->delta, link->cov);
	const PoseEstimate local = builder_->openMap().robotPose();
	return composeEstimates(start, local.mean, local.cov);
}

Estimate DeadReckoningJoiner::estimate() const
{
	Estimate e;
	e.robot = robotPose();
	for (const auto& [id, lm] : landmarks_)
	{
		const double n = static_cast<double>(lm.copies);
		e.landmarks.push_back({id, lm.position_sum / n, lm.covariance_sum / n});
	}
	return e;
}

CostFigures DeadReckoningJoiner::costFigures() const
{
	CostFigures c;
	c.state_dim = 3 * end_poses_.size() + 2 * landmarks_.size();
	c.poses_in_state = end_poses_.size();
	c.counters.emplace_back("maps_fused", static_cast<double>(end_poses_.size()));
	return c;
}

std::optional<std::vector<StepReport>> DeadReckoningJoiner::finalReports() const
{
	if (!finished_ || steps_ == 0) return std::nullopt;
	return final_reports_;
}

StepReport DeadReckoningJoiner::mapReport(std::size_t k) const
{
	return k >= 1 && k <= map_reports_.size() ? map_reports_[k - 1] : StepReport{};
}

PoseEstimate DeadReckoningJoiner::startPoseOf(const LocalMap& map) const
{
	const PoseEstimate previous_end = end_poses_.empty() ? PoseEstimate{} : end_poses_.back();
	if (!map.link) return previous_end;
	return composeEstimates(previous_end, map.link->delta, map.link->cov);
}

std::vector<DeadReckoningJoiner::PlacedFeature> DeadReckoningJoiner::placeFeatures(
	const LocalMap& map, const PoseEstimate& start) const
{
	const Eigen::MatrixXd P = covarianceOf(map);
	const Pose2 s = start.mean;
	const double c = std::cos(s.z()), sn = std::sin(s.z());
	Eigen::Matrix2d R;
	R << c, -sn, sn, c;
	std::vector<PlacedFeature> placed;
	for (std::size_t i = 0; i < map.features.size(); ++i)
	{
		const Eigen::Vector2d p = map.features[i].position;
		Eigen::Matrix<double, 2, 3> J_start;  // of the global point w.r.t. the start pose
		J_start << 1, 0, -sn * p.x() - c * p.y(),  //
			0, 1, c * p.x() - sn * p.y();
		const auto at = static_cast<Eigen::Index>(3 + 2 * i);
		placed.push_back({transformPoint(s, p), J_start * start.cov * J_start.transpose() +
													R * P.block<2, 2>(at, at) * R.transpose()});
	}
	return placed;
}

StepReport DeadReckoningJoiner::associate(const LocalMap& map, const std::vector<PlacedFeature>& placed)
{
	StepReport report;
	std::set<LandmarkId> taken;	 // a landmark takes at most one feature of a map
	for (std::size_t i = 0; i < placed.size(); ++i)
	{
		if (params_.match_distance_m <= 0)
		{
			const LandmarkId id = map.features[i].id;
			report.associations.push_back({landmarks_.count(id) ? Association::Kind::Matched : Association::Kind::New, id});
			continue;
		}
		std::optional<LandmarkId> nearest;
		double best = params_.match_distance_m;
		for (const auto& [id, lm] : landmarks_)
		{
			const double d = (lm.position_sum / static_cast<double>(lm.copies) - placed[i].position).norm();
			if (d < best && !taken.count(id)) best = d, nearest = id;
		}
		if (nearest)
		{
			taken.insert(*nearest);
			report.associations.push_back({Association::Kind::Matched, *nearest});
		}
		else
			report.associations.push_back({Association::Kind::New, next_own_id_++});
	}
	return report;
}

void DeadReckoningJoiner::joinLocalMap(const LocalMap& map)
{
	if (map.index != end_poses_.size() + 1)
		throw std::logic_error(
			"DeadReckoningJoiner: local map " + std::to_string(map.index) + " after " +
			std::to_string(end_poses_.size()) + " maps");
	const auto t0 = Clock::now();
	std::vector<LandmarkId> ids;
	for (const auto& f : map.features) ids.push_back(f.id);
	ids_seen_.push_back(ids);

	const PoseEstimate start = startPoseOf(map);
	const std::vector<PlacedFeature> placed = placeFeatures(map, start);
	const auto t_association = Clock::now();
	StepReport report = associate(map, placed);
	const double association_s = secondsSince(t_association);
	for (std::size_t i = 0; i < placed.size(); ++i)
	{
		Landmark& lm = landmarks_[report.associations[i].id];
		lm.position_sum += placed[i].position;
		lm.covariance_sum += placed[i].covariance;
		++lm.copies;
	}
	const Eigen::MatrixXd P = covarianceOf(map);
	end_poses_.push_back(composeEstimates(start, map.end_pose, P.topLeftCorner<3, 3>()));
	map_reports_.push_back(report);
	settleStepReports(map, report);
	costs_.push_back({map.index, secondsSince(t0), association_s, costFigures().state_dim});
}

void DeadReckoningJoiner::settleStepReports(const LocalMap& map, const StepReport& report)
{
	std::map<LandmarkId, std::size_t> feature_index;
	for (std::size_t i = 0; i < map.features.size(); ++i) feature_index[map.features[i].id] = i;
	for (StepReport step : map.step_reports)
	{
		for (auto& a : step.associations)
		{
			if (a.kind == Association::Kind::Rejected) continue;
			const auto i = feature_index.find(a.id);
			if (i == feature_index.end())
			{
				a = {Association::Kind::Rejected, -1};
				continue;
			}
			a.id = report.associations[i->second].id;
			a.kind = settled_ids_.insert(a.id).second ? Association::Kind::New : Association::Kind::Matched;
		}
		final_reports_.push_back(std::move(step));
	}
}

}  // namespace esif::test
