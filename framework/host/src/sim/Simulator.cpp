#include <esif/core/Errors.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/GzArchive.h>
#include <esif/formats/RawlogWriter.h>
#include <esif/safeio/AtomicFile.h>
#include <esif/formats/MeasurementTruth.h>
#include <esif/sim/Simulator.h>
#include "FeatureGrid.h"

#include "MeasurementOutliers.h"

#include <mrpt/core/Clock.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt/serialization/CArchive.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>

namespace esif
{
namespace
{
constexpr double kDegToRad = M_PI / 180.0;

/// Diagonal added to every odometry covariance: the mid-point model's
/// covariance has rank 2 (three outputs driven by two noises), and filters
/// need it positive definite.
constexpr double kCovarianceFloor = 1e-10;

/// The robot switches to a new waypoint once this close to the current one [m].
constexpr double kWaypointReach_m = Scenario::kWaypointReach_m;

/// Time constant of the heading controller [s]: the commanded turn rate is
/// heading error / tau, saturated at the maximum turn rate.
constexpr double kHeadingTimeConstant_s = 0.5;

/// Draws per waypoint before settling for the farthest candidate.
constexpr int kWaypointDraws = 100;

/// Seed offset of the noise generator: the path has its own generator, so a
/// change of noise levels keeps the same true trajectory for a given seed.
constexpr std::uint32_t kNoiseSeedOffset = 0x9E3779B9u;

/// Seed offsets of the outlier generator (wrong IDs, clutter) and of the
/// twins' directions: each has its own, so turning one on changes nothing
/// the others draw.
constexpr std::uint32_t kOutlierSeedOffset = 0x85EBCA6Bu;
constexpr std::uint32_t kLayoutSeedOffset = 0xC2B2AE35u;

/// Waypoint tour steered with a saturated proportional heading controller:
/// the scripted waypoints in order (repeated), or, without a script, uniform
/// random waypoints inside the square minus a margin.
class WaypointTour
{
   public:
	WaypointTour(const Scenario& s, std::uint32_t seed) : s_(s), rng_(seed), script_(s.scriptedWaypoints())
	{
		lo_ = s.waypoint_margin_m;
		hi_ = s.world_size_m - s.waypoint_margin_m;
		max_turn_rate_ = s.max_turn_rate_deg_s * kDegToRad;
		// A waypoint inside one of the robot's two minimum turning circles
		// cannot be reached by a constant-speed unicycle (it would orbit it);
		// one farther than a turning diameter lies outside both.
		min_distance_ = 2.0 * (s.speed_mps / max_turn_rate_) + kWaypointReach_m;
	}

	/// True turn rate [rad/s] to apply from `pose`.
	double turnRate(const Pose2& pose)
	{
		const Eigen::Vector2d to_wp = waypoint_ - pose.head<2>();
		if (!has_waypoint_ || to_wp.norm() < kWaypointReach_m || steps_left_ <= 0) pickWaypoint(pose);
		--steps_left_;
		const Eigen::Vector2d d = waypoint_ - pose.head<2>();
		const double error = wrapAngle(std::atan2(d.y(), d.x()) - pose.z());
		const double tau = std::max(kHeadingTimeConstant_s, 2.0 * s_.dt_s);
		return std::clamp(error / tau, -max_turn_rate_, max_turn_rate_);
	}

   private:
	void pickWaypoint(const Pose2& pose)
	{
		Eigen::Vector2d best = pose.head<2>();
		double best_distance = -1;
		if (!script_.empty())
		{
			// Scenario::validate() spaces the script so each waypoint is
			// reachable from wherever the previous one was reached.
			best = script_[next_scripted_];
			best_distance = (best - pose.head<2>()).norm();
			next_scripted_ = (next_scripted_ + 1) % script_.size();
		}
		else
			for (int i = 0; i < kWaypointDraws; ++i)
			{
				const Eigen::Vector2d c(rng_.drawUniform(lo_, hi_), rng_.drawUniform(lo_, hi_));
				const double distance = (c - pose.head<2>()).norm();
				if (distance > best_distance) best = c, best_distance = distance;
				if (distance >= min_distance_) break;
			}
		waypoint_ = best;
		has_waypoint_ = true;
		// Safety net against orbiting (e.g. a waypoint area smaller than the
		// turning circle): give up on a waypoint after twice the time of a
		// full turn plus the straight drive.
		const double budget_s = 2.0 * (best_distance / s_.speed_mps + 2 * M_PI / max_turn_rate_);
		steps_left_ = static_cast<long>(std::ceil(budget_s / s_.dt_s));
	}

	const Scenario& s_;
	mrpt::random::CRandomGenerator rng_;
	std::vector<Eigen::Vector2d> script_;  ///< scripted waypoints; empty: random ones
	std::size_t next_scripted_ = 0;	 ///< index in script_ of the next waypoint to head for
	double lo_ = 0, hi_ = 0, max_turn_rate_ = 0, min_distance_ = 0;
	Eigen::Vector2d waypoint_ = Eigen::Vector2d::Zero();
	bool has_waypoint_ = false;
	long steps_left_ = 0;
};

/// Jacobian of midpointIncrement() with respect to (distance, angle).
Eigen::Matrix<double, 3, 2> midpointJacobian(double d, double a)
{
	const double c = std::cos(a / 2), s = std::sin(a / 2);
	Eigen::Matrix<double, 3, 2> G;
	G << c, -d / 2 * s,	 //
		s, d / 2 * c,  //
		0, 1;
	return G;
}

/// Odometry increment covariance for noisy readings (d, a) with variances
/// var_d = (std_speed dt)^2, var_a = (std_turn_rate dt)^2.
Eigen::Matrix3d odometryCovariance(double d, double a, double var_d, double var_a)
{
	const auto G = midpointJacobian(d, a);
	Eigen::Matrix3d cov = G * Eigen::Vector2d(var_d, var_a).asDiagonal() * G.transpose();
	// G has rank 2, so first order leaves one direction with zero variance.
	// The second-order cross term (d/dd d/da of the increment) * n_d * n_a
	// lies partly in that direction; adding its covariance var_d var_a h h^T
	// keeps the model consistent for any dt (a bare floor would be
	// overconfident there for large dt).
	const Eigen::Vector3d h(-std::sin(a / 2) / 2, std::cos(a / 2) / 2, 0);
	cov += var_d * var_a * h * h.transpose();
	cov += kCovarianceFloor * Eigen::Matrix3d::Identity();
	// Exactly symmetric, as MRPT stores only one triangle: the step handed to
	// the sink is then bit-identical to what a reader gets from the rawlog.
	return (cov + cov.transpose()) / 2;
}

/// A step's rawlog IDs beside its true ones.
std::vector<MeasurementIds> measurementIdsOf(const SimulatedStep& step)
{
	std::vector<MeasurementIds> out;
	for (std::size_t i = 0; i < step.input.scan->measurements.size(); ++i)
		out.push_back({*step.input.scan->measurements[i].id, step.true_ids[i]});
	return out;
}

}  // namespace

Simulator::Simulator(const Scenario& scenario) : scenario_(scenario)
{
	scenario_.validate();
	const int n = scenario_.features_per_side;
	const double spacing = scenario_.featureSpacing();
	features_.reserve(static_cast<std::size_t>(n) * n);
	feature_ids_.reserve(static_cast<std::size_t>(n) * n);
	for (int row = 0; row < n; ++row)
		for (int col = 0; col < n; ++col)
		{
			const Eigen::Vector2d p((col + 0.5) * spacing, (row + 0.5) * spacing);
			// The grid index stays the ID: removed features leave gaps in the
			// IDs, and the remaining features keep the IDs they have without
			// the band.
			if (scenario_.inFeaturelessBand(p.x())) continue;
			features_.push_back(p);
			feature_ids_.push_back(static_cast<LandmarkId>(row * n + col));
		}
	if (scenario_.hasClusterPairs()) addClusterTwins();
}

void Simulator::addClusterTwins()
{
	mrpt::random::CRandomGenerator layout(static_cast<std::uint32_t>(scenario_.seed) + kLayoutSeedOffset);
	const LandmarkId twin_offset = LandmarkId(scenario_.features_per_side) * scenario_.features_per_side;
	const std::size_t grid_count = features_.size();
	for (std::size_t i = 0; i < grid_count; ++i)
	{
		const double direction = layout.drawUniform(-M_PI, M_PI);
		features_.push_back(
			features_[i] + scenario_.cluster_pair_distance_m * Eigen::Vector2d(std::cos(direction), std::sin(direction)));
		feature_ids_.push_back(feature_ids_[i] + twin_offset);
	}
}

Pose2 Simulator::midpointIncrement(double distance_m, double angle_rad)
{
	return {distance_m * std::cos(angle_rad / 2), distance_m * std::sin(angle_rad / 2), angle_rad};
}

SimulationSummary Simulator::simulate(const std::function<void(const SimulatedStep&)>& sink) const
{
	const Scenario& s = scenario_;
	const auto seed = static_cast<std::uint32_t>(s.seed);
	WaypointTour tour(s, seed);
	// The noise may have its own seed (noise_seed): new noise, same path.
	const std::uint32_t noise_seed = s.effectiveNoiseSeed();
	mrpt::random::CRandomGenerator noise(noise_seed + kNoiseSeedOffset);
	MeasurementOutliers outliers(s, features_, feature_ids_, noise_seed + kOutlierSeedOffset);

	const double dt = s.dt_s;
	const double var_d = std::pow(s.std_speed_mps * dt, 2);
	const double var_a = std::pow(s.std_turn_rate_deg_s * kDegToRad * dt, 2);
	const double std_bearing = s.std_bearing_deg * kDegToRad;
	const double half_fov = s.sensor_fov_deg * kDegToRad / 2;
	const Pose2 sensor_on_robot(s.sensor_x_m, s.sensor_y_m, wrapAngle(s.sensor_yaw_deg * kDegToRad));

	Eigen::Matrix2d measurement_cov = Eigen::Matrix2d::Zero();
	measurement_cov.diagonal() << s.std_range_m * s.std_range_m, std_bearing * std_bearing;

	SimulationSummary summary;
	summary.features = features_.size();
	std::vector<bool> seen(features_.size(), false);
	std::size_t sparse_run = 0;	 // consecutive scans so far with fewer than two measurements
	std::size_t empty_run = 0;	// consecutive scans so far without measurements

	// A scan tests only the features of the cells its range reaches, in
	// index order as a loop over all of them would: the same rawlog, bit for
	// bit, at a cost that does not grow with the world.
	const FeatureGrid grid(features_, s.sensor_max_range_m);
	std::vector<std::size_t> nearby;

	Pose2 pose(s.start_x_m, s.start_y_m, wrapAngle(s.start_yaw_deg * kDegToRad));
	for (int k = 0; k < s.steps; ++k)
	{
		SimulatedStep step;
		step.input.index = static_cast<std::size_t>(k);
		step.input.time_s = k * dt;

		OdometryIncrement odo;
		if (k == 0)
		{
			// The first scan is taken at the start pose: a zero move keeps
			// MRPT's action/sensory-frame pairing from dropping it.
			odo.delta = Pose2(0, 0, 0);
			odo.cov = kCovarianceFloor * Eigen::Matrix3d::Identity();
		}
		else
		{
			const double v = s.speed_mps;
			const double w = tour.turnRate(pose);
			// Odometry reads the true controls plus white noise; its
			// increment uses the same motion model as the true robot, so its
			// error comes from the noise alone.
			const double v_read = v + s.std_speed_mps * noise.drawGaussian1D_normalized();
			const double w_read = w + s.std_turn_rate_deg_s * kDegToRad * noise.drawGaussian1D_normalized();
			const double d = v_read * dt, a = w_read * dt;
			odo.delta = midpointIncrement(d, a);
			odo.cov = odometryCovariance(d, a, var_d, var_a);

			pose = compose(pose, midpointIncrement(v * dt, w * dt));
			summary.path_length_m += v * dt;
		}
		step.input.odometry = odo;

		Scan scan;
		scan.sensor_on_robot = sensor_on_robot;
		scan.max_range_m = s.sensor_max_range_m;
		scan.fov_rad = s.sensor_fov_deg * kDegToRad;
		const Pose2 sensor = compose(pose, sensor_on_robot);
		grid.near(Eigen::Vector2d(sensor.x(), sensor.y()), s.sensor_max_range_m, nearby);
		for (const std::size_t i : nearby)
		{
			const Eigen::Vector2d p =
				inverseCompose(sensor, Pose2(features_[i].x(), features_[i].y(), 0)).head<2>();
			const double range = p.norm();
			const double bearing = std::atan2(p.y(), p.x());
			if (range > s.sensor_max_range_m || std::abs(bearing) > half_fov) continue;
			RangeBearing m;
			m.range_m = std::max(0.0, range + s.std_range_m * noise.drawGaussian1D_normalized());
			m.bearing_rad = wrapAngle(bearing + std_bearing * noise.drawGaussian1D_normalized());
			m.cov = measurement_cov;
			m.id = feature_ids_[i];
			scan.measurements.push_back(m);
			step.true_ids.push_back(feature_ids_[i]);
			seen[i] = true;
		}
		outliers.apply(scan, step.true_ids, measurement_cov);
		summary.measurements += scan.measurements.size();
		if (scan.measurements.empty()) ++summary.scans_without_measurements;
		if (scan.measurements.size() == 1) ++summary.scans_with_one_measurement;
		sparse_run = scan.measurements.size() < 2 ? sparse_run + 1 : 0;
		summary.longest_run_below_two_measurements = std::max(summary.longest_run_below_two_measurements, sparse_run);
		empty_run = scan.measurements.empty() ? empty_run + 1 : 0;
		summary.longest_run_without_measurements = std::max(summary.longest_run_without_measurements, empty_run);
		step.input.scan = std::move(scan);
		step.true_pose = pose;
		sink(step);
		++summary.steps;
	}
	summary.features_seen = static_cast<std::size_t>(std::count(seen.begin(), seen.end(), true));
	summary.wrong_id_measurements = outliers.wrongIdCount();
	summary.spurious_measurements = outliers.spuriousCount();
	return summary;
}

SimulationSummary Simulator::writeRawlog(const std::string& rawlog_path) const
{
	const auto folder = std::filesystem::path(rawlog_path).parent_path();
	if (!folder.empty()) ensureDirectory(folder.string());

	GroundTruth truth;
	for (std::size_t i = 0; i < features_.size(); ++i) truth.landmarks[feature_ids_[i]] = features_[i];
	truth.path.reserve(static_cast<std::size_t>(scenario_.steps));

	MeasurementTruth measurement_truth;  // kept only when the rawlog's IDs are not the truth
	SimulationSummary summary;
	// Best compression: committed rawlogs stay small, and writing is cheap
	// next to any filter run. Written checked (a full disk is an error).
	writeGzArchiveAtomically(
		rawlog_path,
		[&](mrpt::serialization::CArchive& ar) {
			summary = simulate([&](const SimulatedStep& step) {
				appendStep(ar, step.input, {scenario_.std_range_m, scenario_.std_bearing_deg * kDegToRad});
				truth.path.push_back(step.true_pose);
				if (scenario_.hasOutliers()) measurement_truth.push_back(measurementIdsOf(step));
			});
		},
		9);
	saveGroundTruth(truth, groundTruthPrefixFor(rawlog_path));
	if (scenario_.hasOutliers()) saveMeasurementTruth(measurement_truth, groundTruthPrefixFor(rawlog_path));
	return summary;
}

}  // namespace esif
