#include <esif/relative/FeatureMap.h>

#include <algorithm>
#include <stdexcept>

namespace esif::relative
{
void declareMapLinearisation(ParamBinder& b, MapLinearisation& field)
{
	b.enumeration<MapLinearisation>("map_linearisation", field,
									{{"shared", MapLinearisation::Shared}, {"current", MapLinearisation::Current}},
									"map updates linearised at one point per feature, shared by all updates and moved "
									"only by relinearisation (shared), or at the estimate of their time (current, the "
									"book)");
}

FeatureMap::FeatureMap(const SparseRecoveryParams& params) : core_(params) {}

Eigen::Vector2d FeatureMap::position(LandmarkId id) const { return core_.estimate(var_of_.at(id)); }

VarId FeatureMap::createFeature(LandmarkId id, const Eigen::Vector2d& position, const Eigen::Vector2d& shared_point)
{
	const VarId v = core_.addPoint(position);
	var_of_.emplace(id, v);
	ids_.push_back(id);
	shared_point_.push_back(shared_point);
	return v;
}

std::vector<VarId> FeatureMap::variables(const std::vector<LandmarkId>& ids) const
{
	std::vector<VarId> vars;
	vars.reserve(ids.size());
	for (LandmarkId id : ids) vars.push_back(var_of_.at(id));
	return vars;
}

Eigen::VectorXd FeatureMap::positions(const std::vector<LandmarkId>& ids) const
{
	Eigen::VectorXd xy(2 * ids.size());
	for (std::size_t i = 0; i < ids.size(); ++i) xy.segment<2>(2 * i) = position(ids[i]);
	return xy;
}

Eigen::VectorXd FeatureMap::linearisationPoints(const std::vector<LandmarkId>& ids) const
{
	if (!share_points_) return positions(ids);
	Eigen::VectorXd xy(2 * ids.size());
	for (std::size_t i = 0; i < ids.size(); ++i)
		xy.segment<2>(2 * i) = shared_point_[static_cast<std::size_t>(var_of_.at(ids[i]).value)];
	return xy;
}

void FeatureMap::markSupported(const std::vector<LandmarkId>& ids)
{
	for (LandmarkId id : ids) unsupported_.erase(id);
}

MapUpdate FeatureMap::updateRelative(const std::vector<LandmarkId>& ids, const PointSet& points)
{
	if (ids.size() < 2 || !supported(ids[0]) || !supported(ids[1]))
		throw std::logic_error("D-SLAM map update: the reference pair must be mapped features");
	MapUpdate update;
	Measurement m = relativeMeasurement(points);
	const Eigen::VectorXd& z = m.z;	 // z_map, eq. (3.8)
	const Eigen::Vector2d f1 = position(ids[0]), f2 = position(ids[1]);
	// A new feature is placed twice by eq. (3.14): its estimate from the
	// pair's estimates, and its shared linearisation point from the pair's
	// shared points. The term's points must be one configuration: a point
	// placed from the estimates beside a pair linearised where the map stood
	// before a loop closure moved it (38 m on the 10k city, step 3013) gives
	// its rows a residual of that shift, and the linearised term threw the
	// feature 100 m; D-SLAM stopped as diverged ten steps later.
	const Eigen::VectorXd pair_lin = linearisationPoints({ids[0], ids[1]});
	for (std::size_t i = 2; i < ids.size(); ++i)
		if (!contains(ids[i]))
		{
			const int row = static_cast<int>(2 * i - 3);
			createFeature(ids[i], featureFromPair(f1, f2, z(row + 1), z(row)),
						  featureFromPair(pair_lin.head<2>(), pair_lin.tail<2>(), z(row + 1), z(row)));
			update.new_features.push_back(ids[i]);
		}
	const Eigen::VectorXd x_lin = linearisationPoints(ids);
	std::vector<VarId> vars = variables(ids);
	update.term = relativeTerm(vars, m, x_lin, positions(ids));
	if (keep_terms_)
	{
		update.kept_index = static_cast<long>(terms_.size());
		terms_.push_back({std::move(vars), std::move(m), update.term, x_lin});
	}
	markSupported(ids);
	return update;
}

FeatureMap::Measurement FeatureMap::relativeMeasurement(const PointSet& points)
{
	const ValueJacobian z = relativeGeometry(points.xy);  // z_map, eq. (3.8); dT2
	// Eq. (3.9): R_map = dT2 (dT1 R_old dT1^T) dT2^T; points.cov holds the bracket.
	const Eigen::MatrixXd R_map = z.jacobian * points.cov * z.jacobian.transpose();
	return measurement(z.value, 0.5 * (R_map + R_map.transpose()));
}

FeatureMap::Measurement FeatureMap::measurement(Eigen::VectorXd z, const Eigen::MatrixXd& R)
{
	return {std::move(z), Eigen::LLT<Eigen::MatrixXd>(R)};
}

Eigen::Vector2d FeatureMap::pointIn(const Eigen::VectorXd& state, VarId v) const
{
	return state.segment<2>(core_.information().offset(v));
}

void FeatureMap::termPoints(const KeptTerm& t, const Eigen::VectorXd& state, Eigen::VectorXd& out) const
{
	out.resize(2 * static_cast<Eigen::Index>(t.vars.size()));
	for (std::size_t i = 0; i < t.vars.size(); ++i) out.segment<2>(2 * i) = pointIn(state, t.vars[i]);
}

UpdateTerm FeatureMap::relativeTerm(const std::vector<VarId>& vars, const Measurement& m,
									const Eigen::VectorXd& x_lin, const Eigen::VectorXd& x_now)
{
	// Eq. (3.13): H_map and its Jacobian at x_lin. The core adds
	// J^T R^-1 (nu + J x^) at the current estimate x^, eq. (3.15); at x_lin
	// the term is J^T R^-1 (z - H(x_lin) + J x_lin), hence nu below. It
	// depends on x_lin only, so a term evaluated again at its old x_lin is
	// the old term (undo()).
	const ValueJacobian h = relativeGeometry(x_lin);
	const Eigen::VectorXd nu = relativeDifference(m.z, h.value) + h.jacobian * (x_lin - x_now);
	return core_.addMeasurement(vars, h.jacobian, m.R_factor, nu);
}

double FeatureMap::relativeChangeSince(const std::vector<LandmarkId>& ids, const Eigen::VectorXd& then) const
{
	return relativeChange(positions(ids), then);
}

double FeatureMap::relativeChange(const Eigen::VectorXd& now, const Eigen::VectorXd& then)
{
	const Eigen::Vector2d shift = now.head<2>() - then.head<2>();
	double largest = 0;
	for (Eigen::Index i = 2; i < now.size(); i += 2)
		largest = std::max(largest, (now.segment<2>(i) - then.segment<2>(i) - shift).norm());
	return largest;
}

std::size_t FeatureMap::relinearise(double threshold_m) { return relinearisePass(threshold_m).changed.size(); }

FeatureMap::Pass FeatureMap::relinearisePass(double threshold_m)
{
	Pass pass;
	const Eigen::VectorXd& state = core_.state();
	if (share_points_)
	{
		// Features are the core's variables in order of creation.
		pass.shared_before = shared_point_;
		for (std::size_t i = 0; i < ids_.size(); ++i) shared_point_[i] = pointIn(state, VarId{static_cast<int>(i)});
	}
	Eigen::VectorXd now;
	for (std::size_t k = 0; k < terms_.size(); ++k)
	{
		KeptTerm& t = terms_[k];
		if (!t.active || t.anchor) continue;
		termPoints(t, state, now);
		if (threshold_m > 0 && relativeChange(now, t.linearised_at) <= threshold_m) continue;
		core_.withdraw(t.term);
		t.term = relativeTerm(t.vars, t.measurement, now, now);
		pass.changed.emplace_back(k, std::move(t.linearised_at));
		t.linearised_at = now;
	}
	return pass;
}

void FeatureMap::undo(const Pass& pass)
{
	if (share_points_) shared_point_ = pass.shared_before;
	const Eigen::VectorXd& state = core_.state();
	Eigen::VectorXd now;
	for (const auto& [k, old_lin] : pass.changed)
	{
		KeptTerm& t = terms_[k];
		termPoints(t, state, now);
		core_.withdraw(t.term);
		t.term = relativeTerm(t.vars, t.measurement, old_lin, now);
		t.linearised_at = old_lin;
	}
}

double FeatureMap::cost()
{
	// Read from the whole state once: evaluated on every kept update after
	// each relinearisation pass, per-feature reads cost as much as the rest.
	const Eigen::VectorXd& state = core_.state();
	double total = 0;
	Eigen::VectorXd x, r;
	for (const KeptTerm& t : terms_)
	{
		if (!t.active) continue;
		termPoints(t, state, x);
		r = t.anchor ? Eigen::VectorXd(t.measurement.z - x)
					 : relativeDifference(t.measurement.z, relativeGeometryValue(x));
		t.measurement.R_factor.matrixL().solveInPlace(r);  // |L^-1 r|^2 = r^T R^-1 r
		total += r.squaredNorm();
	}
	return total;
}

namespace
{
constexpr double kCostRiseTolerance = 1e-3;
}

std::size_t FeatureMap::relineariseUntilSettled(double threshold_m, int passes, const Eigen::Vector2d& reference)
{
	std::size_t total = 0;
	double cost_before = 0;
	for (int i = 0; i < passes; ++i)
	{
		const Pass pass = relinearisePass(threshold_m);
		if (pass.changed.empty()) break;
		// The cost reads the estimate only, which the pass has not moved yet.
		if (i == 0) cost_before = cost();
		recover(reference);
		const double cost_after = cost();
		// Passes that relinearise only the terms past threshold_m are not
		// exact Gauss-Newton steps: near the minimum they move the cost
		// either way by a little (31 rises over the 1k city, Victoria Park
		// and MRCLAM, none above 2.4e-4 of the cost). An overshoot
		// multiplies it (x2.3 on MRCLAM robot 3). A cost that is not a
		// number (features on top of each other) counts as a rise.
		if (!(cost_after <= cost_before * (1 + kCostRiseTolerance)))
		{
			undo(pass);
			recover(reference);
			++rejected_passes_;
			break;
		}
		total += pass.changed.size();
		cost_before = cost_after;
	}
	return total;
}

MapUpdate FeatureMap::updateAnchor(const std::vector<LandmarkId>& ids, const PointSet& points)
{
	MapUpdate update;
	for (std::size_t i = 0; i < ids.size(); ++i)
		if (!contains(ids[i]))
		{
			createFeature(ids[i], points.point(static_cast<int>(i)), points.point(static_cast<int>(i)));
			update.new_features.push_back(ids[i]);
		}
	const auto n = static_cast<Eigen::Index>(points.xy.size());
	Measurement m = measurement(points.xy, points.cov);
	std::vector<VarId> vars = variables(ids);
	update.term = core_.addMeasurement(vars, Eigen::MatrixXd::Identity(n, n), m.R_factor, points.xy - positions(ids));
	if (keep_terms_)
	{
		update.kept_index = static_cast<long>(terms_.size());
		terms_.push_back({std::move(vars), std::move(m), update.term, points.xy, true});
	}
	markSupported(ids);
	return update;
}

void FeatureMap::withdraw(const MapUpdate& update)
{
	if (update.kept_index >= 0)
	{
		auto& t = terms_.at(static_cast<std::size_t>(update.kept_index));
		core_.withdraw(t.term);	 // the term as last relinearised
		t.active = false;
	}
	else
		core_.withdraw(update.term);
	for (LandmarkId id : update.new_features) unsupported_.insert(id);
}

void FeatureMap::recover(const Eigen::Vector2d& robot_xy)
{
	core_.setReferencePoint(robot_xy);
	core_.recoverState();
}

StateInformation FeatureMap::stateInformation() const
{
	return core_.stateInformation([&](VarId v) { return StateVariable::landmarkOf(ids_.at(static_cast<std::size_t>(v.value))); });
}

Eigen::MatrixXd FeatureMap::covariance(const std::vector<LandmarkId>& ids) { return core_.covariance(variables(ids)); }

std::vector<LandmarkEstimate> FeatureMap::landmarks()
{
	std::vector<LandmarkEstimate> out;
	if (ids_.empty()) return out;
	const auto marginals = core_.marginalCovariances();
	out.reserve(ids_.size());
	for (std::size_t i = 0; i < ids_.size(); ++i) out.push_back({ids_[i], position(ids_[i]), marginals[i]});
	return out;
}

}  // namespace esif::relative
