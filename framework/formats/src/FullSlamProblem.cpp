/// \file FullSlamProblem.cpp
/// The rawlog replayed into poses, landmarks and factors, with initial values
/// from dead reckoning (eq. 1.3) and first sightings (the inverse of eq. 1.6)
/// or from another run's estimate.

#include <esif/core/Errors.h>
#include <esif/formats/FullSlamProblem.h>
#include <esif/models/RangeBearingModel.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <string>
#include <unordered_map>

namespace esif
{
namespace
{
/// Symmetric (to rounding) and positive definite, all entries finite.
template <int N>
bool isSymmetricPositiveDefinite(const Eigen::Matrix<double, N, N>& m)
{
	if (!m.allFinite()) return false;
	const double scale = m.cwiseAbs().maxCoeff();
	if (!((m - m.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * scale)) return false;
	return Eigen::LLT<Eigen::Matrix<double, N, N>>(m).info() == Eigen::Success;
}

std::string where(const Rawlog& log, std::size_t step)
{
	return log.path + ": step " + std::to_string(step);
}

/// The initial values another run offers: its pose after each step and its
/// finite landmarks.
class RunInitialValues
{
   public:
	RunInitialValues(const RunOutputs& run, std::size_t steps, const std::string& source) : run_(run)
	{
		if (run.trajectory.size() < steps)
			throw InputError(
				source + "/trajectory.tum: has " + std::to_string(run.trajectory.size()) + " poses, the rawlog " +
				std::to_string(steps) + " steps (is it the run of another rawlog?)");
		for (const LandmarkEstimate& l : run.landmarks)
			if (l.mean.allFinite()) landmarks_.emplace(l.id, l.mean);
	}
	Pose2 poseAfterStep(std::size_t k) const { return toPose2(run_.trajectory[k].pose); }
	const Eigen::Vector2d* landmark(LandmarkId id) const
	{
		const auto it = landmarks_.find(id);
		return it == landmarks_.end() ? nullptr : &it->second;
	}

   private:
	const RunOutputs& run_;
	std::unordered_map<LandmarkId, Eigen::Vector2d> landmarks_;
};

/// Adds the pose made by `step`'s odometry, if it moves the robot.
void addOdometry(
	FullSlamProblem& p, const Rawlog& log, const StepInput& step, const RunInitialValues* initial,
	std::size_t& current)
{
	if (!step.odometry || isStandStill(*step.odometry)) return;
	const OdometryIncrement& u = *step.odometry;
	if (!isSymmetricPositiveDefinite<3>(u.cov))
		throw InputError(
			where(log, step.index) + ": odometry covariance is not symmetric positive definite (no information "
									 "matrix for the factor)");
	OdometryFactor f;
	f.step = step.index;
	f.from = current;
	f.to = p.poses.size();
	f.delta = u.delta;
	f.cov = u.cov;
	p.odometry.push_back(f);
	p.poses.push_back(initial ? initial->poseAfterStep(step.index) : compose(p.poses[current], f.delta));
	current = f.to;
}

/// Adds the factors of `step`'s measurements that carry a landmark ID, and
/// the landmarks seen for the first time.
void addObservations(
	FullSlamProblem& p, const Rawlog& log, const StepInput& step, const RunInitialValues* initial,
	std::size_t current)
{
	if (!step.scan) return;
	const Pose2 sensor = step.scan->sensor_on_robot;
	const auto& ms = step.scan->measurements;
	for (std::size_t j = 0; j < ms.size(); ++j)
	{
		const RangeBearing& m = ms[j];
		if (!m.id)
		{
			++p.measurements_without_id;
			continue;
		}
		if (!isSymmetricPositiveDefinite<2>(m.cov))
			throw InputError(
				where(log, step.index) + ": measurement " + std::to_string(j) +
				": covariance is not symmetric positive definite");
		if (!p.landmarks.count(*m.id))
		{
			const Eigen::Vector2d* guess = initial ? initial->landmark(*m.id) : nullptr;
			p.landmarks.emplace(
				*m.id,
				guess ? *guess : landmarkFromRangeBearing(p.poses[current], sensor, m.range_m, m.bearing_rad).position);
		}
		p.observations.push_back({step.index, j, current, *m.id, m.range_m, m.bearing_rad, m.cov, sensor});
	}
}
}  // namespace

FullSlamProblem buildFullSlamProblem(const Rawlog& log, const RunOutputs* initial, const std::string& initial_source)
{
	std::optional<RunInitialValues> run;
	if (initial) run.emplace(*initial, log.steps.size(), initial_source);
	FullSlamProblem p;
	p.poses.push_back(Pose2::Zero());
	std::size_t current = 0;
	for (const StepInput& step : log.steps)
	{
		addOdometry(p, log, step, run ? &*run : nullptr, current);
		addObservations(p, log, step, run ? &*run : nullptr, current);
		p.step_pose.push_back(current);
		p.step_time_s.push_back(step.time_s);
	}
	return p;
}

}  // namespace esif
