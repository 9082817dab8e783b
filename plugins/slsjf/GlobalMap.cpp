#include "GlobalMap.h"

#include "ObservabilityConstraint.h"

#include <esif/core/Errors.h>
#include <esif/models/LocalMapObservation.h>

#include <algorithm>
#include <cmath>

namespace esif::slsjf
{
GlobalMap::GlobalMap(const SparseRecoveryParams& params, FusionJacobians jacobians)
	: params_(params), jacobians_(jacobians), core_(std::make_unique<SparseInformationCore>(params))
{
}

VarId GlobalMap::newPose(const Pose2& initial)
{
	first_estimates_.push_back(initial);
	return core_->addPose(initial);
}

VarId GlobalMap::newPoint(const Eigen::Vector2d& initial)
{
	first_estimates_.push_back(initial);
	return core_->addPoint(initial);
}

GlobalMap::LinearisationPoint GlobalMap::fusionPoint() const
{
	if (jacobians_ == FusionJacobians::FirstEstimates) return [this](VarId v) { return first_estimates_[v.value]; };
	return [this](VarId v) { return core_->estimate(v); };
}

std::optional<GlobalMap::LinearisationPoint> GlobalMap::nullSpacePoint() const
{
	if (jacobians_ != FusionJacobians::ObservabilityConstrained) return std::nullopt;
	return LinearisationPoint([this](VarId v) { return first_estimates_[v.value]; });
}

namespace
{
/// J projected onto the rigid-motion null space of `vars` at `at`.
Eigen::MatrixXd constrained(
	const Eigen::MatrixXd& J, const std::vector<VarId>& vars, const std::function<Eigen::VectorXd(VarId)>& at)
{
	std::vector<Eigen::VectorXd> points;
	for (const VarId v : vars) points.push_back(at(v));
	return constrainToNullSpace(J, rigidMotionDirections(points));
}
}  // namespace

Pose2 GlobalMap::startEstimate(const std::optional<VarId>& start) const
{
	return start ? pose(*start) : Pose2::Zero();
}

std::optional<VarId> GlobalMap::featureVar(LandmarkId id) const
{
	const auto it = var_of_id_.find(id);
	if (it == var_of_id_.end()) return std::nullopt;
	return it->second;
}

std::optional<VarId> GlobalMap::startPose(const LocalMap& map)
{
	const std::optional<VarId> previous_end = fused_.empty() ? std::nullopt : std::optional<VarId>(fused_.back().end);
	if (!map.link) return previous_end;
	// Eq. (5.4)-(5.6): X_(k+1)s = f(X_ke, u) + w, initialised at f(X_ke^, u).
	const Pose2 u = map.link->delta;
	const VarId start = newPose(compose(startEstimate(previous_end), u));
	++poses_;
	links_.push_back({previous_end, start, u, map.link->cov});
	addLinkTerm(*core_, links_.back(), fusionPoint(), nullSpacePoint());
	return start;
}

VarId GlobalMap::addFeature(LandmarkId proposed, const Eigen::Vector2d& initial, LandmarkId& id)
{
	id = ids_.allocate(proposed, [&](LandmarkId candidate) { return var_of_id_.count(candidate) > 0; });
	const VarId v = newPoint(initial);
	var_of_id_[id] = v;
	id_of_var_[v.value] = id;
	feature_vars_.push_back(v);
	return v;
}

void GlobalMap::fuse(const LocalMap& map, std::optional<VarId> start, StepReport& decisions, const MapExtent& extent)
{
	std::vector<bool> keep(map.features.size());
	for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = decisions.associations[i].kind != Association::Kind::Rejected;

	FusedMap fused{map.index, std::nullopt, start, VarId{}, {}, keepFeatures(map, keep), extent};
	if (map.steps > 0) fused.last_step = map.last_step;
	const Pose2 s = startEstimate(start);
	// Eq. (5.7): new features and the end pose from the start pose; these
	// are only linearisation points, the map's information is fused below.
	fused.end = newPose(compose(s, map.end_pose));
	++poses_;
	for (const std::size_t i : fused.observation.kept)
	{
		auto& a = decisions.associations[i];
		if (a.kind == Association::Kind::New)
			fused.features.push_back(addFeature(a.id, pointFromFrame(s, map.features[i].position).value, a.id));
		else if (const auto v = featureVar(a.id))
			fused.features.push_back(*v);
		else
			throw std::logic_error("SLSJF: local map " + std::to_string(map.index) + " matched unknown feature " +
								   std::to_string(a.id));
	}
	addMapTerm(*core_, fused, fusionPoint(), nullSpacePoint());
	fused_.push_back(std::move(fused));
	core_->setReferencePoint(pose(fused_.back().end).head<2>());
	// Eq. (5.14), solved where read: the next fusion reads its own
	// features and the last end pose, a few paths of the factor.
	core_->recoverStateOnDemand();
}

StateInformation GlobalMap::stateInformation() const
{
	std::map<int, const FusedMap*> map_of_end;
	for (const FusedMap& f : fused_) map_of_end[f.end.value] = &f;
	return core_->stateInformation(
		[&](VarId v)
		{
			if (const auto id = id_of_var_.find(v.value); id != id_of_var_.end())
				return StateVariable::landmarkOf(id->second);
			if (const auto end = map_of_end.find(v.value); end != map_of_end.end())
				return StateVariable::poseOf(end->second->last_step, end->second->index);
			return StateVariable::poseOf(std::nullopt);
		});
}

void GlobalMap::addLinkTerm(
	SparseInformationCore& core, const LinkTerm& link, const LinearisationPoint& at,
	const std::optional<LinearisationPoint>& null_space_at)
{
	// F = X_s - f(X_e, u) = 0 + w (eq. 5.5): innovation -F(x^), Jacobian
	// [-df/dX_e, I]. The odometry's covariance Q is the increment's, in X_e's
	// frame (as every StepInput's): eq. 5.4's additive w has df/du Q df/du^T.
	const Pose2 e = link.from ? Pose2(core.estimate(*link.from)) : Pose2::Zero();
	const Pose2 s = core.estimate(link.to);
	const ComposeJacobians df = composeJacobians(link.from ? Pose2(at(*link.from)) : Pose2::Zero(), link.u);
	const Eigen::Matrix3d W = df.d_b * link.Q * df.d_b.transpose();
	Eigen::Vector3d innovation = compose(e, link.u) - s;
	innovation(2) = wrapAngle(innovation(2));
	if (!link.from)
	{
		core.addMeasurement({link.to}, Eigen::Matrix3d::Identity(), W, innovation);
		return;
	}
	Eigen::MatrixXd J(3, 6);
	J << -df.d_a, Eigen::Matrix3d::Identity();
	if (null_space_at) J = constrained(J, {*link.from, link.to}, *null_space_at);
	core.addMeasurement({*link.from, link.to}, J, 0.5 * (W + W.transpose()), innovation);
}

void GlobalMap::addMapTerm(
	SparseInformationCore& core, const FusedMap& map, const LinearisationPoint& at,
	const std::optional<LinearisationPoint>& null_space_at)
{
	// The innovation at the current estimate, the Jacobian where `at` says.
	std::vector<Eigen::Vector2d> features, features_at;
	for (const VarId v : map.features)
	{
		features.push_back(core.estimate(v));
		features_at.push_back(at(v));
	}
	const Pose2 s = map.start ? Pose2(core.estimate(*map.start)) : Pose2::Zero();
	const Pose2 s_at = map.start ? Pose2(at(*map.start)) : Pose2::Zero();
	Eigen::VectorXd innovation = map.observation.z - predictLocalMap(s, core.estimate(map.end), features).h;  // eq. (5.8)
	innovation(2) = wrapAngle(innovation(2));
	const LocalMapPrediction h = predictLocalMap(s_at, at(map.end), features_at);

	std::vector<VarId> vars;
	if (map.start) vars.push_back(*map.start);
	vars.push_back(map.end);
	vars.insert(vars.end(), map.features.begin(), map.features.end());
	Eigen::MatrixXd J(h.h.size(), (map.start ? 3 : 0) + h.d_state.cols());
	if (map.start)
		J << h.d_start, h.d_state;
	else
		J = h.d_state;
	// Only a map seen from a variable start is relative; map 1, from the
	// constant origin, fixes the frame.
	if (map.start && null_space_at) J = constrained(J, vars, *null_space_at);
	core.addInformationMeasurement(vars, J, map.observation.information, innovation);  // eq. (5.9)
}

std::unique_ptr<SparseInformationCore> GlobalMap::rebuiltCore() const
{
	auto fresh = std::make_unique<SparseInformationCore>(params_);
	const InformationForm& info = core_->information();
	for (int v = 0; v < info.variableCount(); ++v)
	{
		const Eigen::VectorXd x = core_->estimate(VarId{v});
		if (info.kind(VarId{v}) == VarKind::Pose2)
			fresh->addPose(x);
		else
			fresh->addPoint(x);
	}
	// Gauss-Newton: every term relinearised at the current estimate.
	const LinearisationPoint current = [&fresh](VarId v) { return fresh->estimate(v); };
	for (const auto& link : links_) addLinkTerm(*fresh, link, current);
	for (const auto& map : fused_) addMapTerm(*fresh, map, current);
	if (!fused_.empty()) fresh->setReferencePoint(pose(fused_.back().end).head<2>());
	return fresh;
}

namespace
{
/// Largest change between two states: metres for positions, radians
/// (wrapped) for headings.
double largestChange(const InformationForm& info, const Eigen::VectorXd& before, const Eigen::VectorXd& after)
{
	double change = 0;
	for (int v = 0; v < info.variableCount(); ++v)
	{
		const int o = info.offset(VarId{v});
		change = std::max(change, (after.segment<2>(o) - before.segment<2>(o)).cwiseAbs().maxCoeff());
		if (info.kind(VarId{v}) == VarKind::Pose2) change = std::max(change, std::abs(wrapAngle(after(o + 2) - before(o + 2))));
	}
	return change;
}

}  // namespace

int GlobalMap::relinearise(int max_iterations, double tolerance)
{
	for (int iteration = 1; iteration <= max_iterations; ++iteration)
	{
		const Eigen::VectorXd before = core_->state();
		auto fresh = rebuiltCore();
		fresh->recoverState();
		const double change = largestChange(fresh->information(), before, fresh->state());
		retired_ += core_->counters();
		core_ = std::move(fresh);
		if (change <= tolerance) return restartFirstEstimates(), iteration;
	}
	restartFirstEstimates();
	return max_iterations;
}

void GlobalMap::restartFirstEstimates()
{
	for (std::size_t v = 0; v < first_estimates_.size(); ++v)
		first_estimates_[v] = core_->estimate(VarId{static_cast<int>(v)});
}

SparseCounters GlobalMap::counters() const
{
	SparseCounters total = core_->counters();
	total += retired_;
	return total;
}

}  // namespace esif::slsjf
