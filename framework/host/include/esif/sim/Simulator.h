#pragma once
/// \file Simulator.h
/// The book's simulated experiments (Sec. 3.5, 4.6.1, 4.6.2): a unicycle robot
/// with odometry and a range-bearing sensor drives a random (or scripted)
/// waypoint tour in a square world of point features on a grid (optionally
/// with a featureless band), and the run is written as a standard MRPT rawlog
/// plus MRPT-style ground-truth files.
///
/// Conventions of the output:
/// - landmark ID = 0-based grid index, row-major from the bottom-left
///   feature (ID = row * features_per_side + column); the ground-truth file
///   uses the same IDs; features removed by a featureless band leave their
///   IDs unused, so the IDs then have gaps; a grid feature's twin
///   (cluster_pair_distance_m) has its ID + features_per_side^2; spurious
///   returns have IDs from Scenario::clutterIdBase() up, of no landmark;
/// - step k holds the odometry increment from pose k-1 to pose k (step 0: a
///   zero increment) and the scan taken at pose k; ground-truth path row k is
///   pose k;
/// - a noisy range below zero is clamped to 0 (it only happens for a feature
///   within a few sigma of the sensor);
/// - a noisy range may exceed sensor_max_range_m: visibility is decided on the
///   true range, as a real sensor detects on the true geometry.

#include <esif/core/StepInput.h>
#include <esif/models/Se2.h>
#include <esif/sim/Scenario.h>

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// One simulated step: what the sensors report, and where the robot truly was.
struct SimulatedStep
{
	/// Odometry (always set; zero increment at step 0) and scan (always set,
	/// possibly without measurements), exactly as written to the rawlog.
	StepInput input;
	Pose2 true_pose;  ///< true robot pose when the scan was taken
	/// The true landmark of each measurement (parallel to the scan's
	/// measurements): its rawlog ID unless Scenario::wrong_id_rate misread
	/// it, none for a spurious return.
	std::vector<std::optional<LandmarkId>> true_ids;
};

/// Counts of a finished simulation.
struct SimulationSummary
{
	std::size_t steps = 0;	///< rawlog steps (= scans = ground-truth path rows)
	std::size_t measurements = 0;  ///< range-bearing measurements over all scans
	std::size_t features = 0;  ///< features in the world
	std::size_t features_seen = 0;	///< features measured at least once
	double path_length_m = 0;  ///< length of the true path [m]
	std::size_t scans_without_measurements = 0;	 ///< scans that measure no feature
	std::size_t scans_with_one_measurement = 0;	 ///< scans that measure exactly one feature
	/// Longest run of consecutive scans with fewer than two measurements:
	/// scans that cannot locate the robot relative to the map on their own
	/// (book Sec. 3.4.1, admissible measurements).
	std::size_t longest_run_below_two_measurements = 0;
	/// Longest run of consecutive scans that measure nothing (long stretches
	/// without any landmark, or clutter, in view).
	std::size_t longest_run_without_measurements = 0;
	/// Measurements carrying another landmark's ID (Scenario::wrong_id_rate).
	std::size_t wrong_id_measurements = 0;
	/// Spurious returns (Scenario::spurious_rate), included in `measurements`.
	std::size_t spurious_measurements = 0;

	/// Mean number of measurements per scan.
	double meanMeasurementsPerScan() const { return steps ? double(measurements) / steps : 0.0; }
};

class Simulator
{
   public:
	/// Validates the scenario (throws ConfigError) and lays out the features.
	explicit Simulator(const Scenario& scenario);

	const Scenario& scenario() const { return scenario_; }

	/// True feature positions in the world frame, in grid order, then the
	/// twins (Scenario::cluster_pair_distance_m) in the order of their grid
	/// features; the landmark ID of features()[i] is featureIds()[i], which is
	/// i when there is no featureless band and no twin.
	const std::vector<Eigen::Vector2d>& features() const { return features_; }

	/// Landmark IDs of features(), increasing: grid indices, then for the
	/// twins their grid feature's ID + features_per_side^2.
	const std::vector<LandmarkId>& featureIds() const { return feature_ids_; }

	/// Runs the whole scenario, handing each step to `sink` in order. The
	/// random generators are re-seeded on every call, so two calls produce
	/// identical steps.
	SimulationSummary simulate(const std::function<void(const SimulatedStep&)>& sink) const;

	/// Runs the scenario and writes `rawlog_path` (gz-compressed rawlog in
	/// actions/sensory-frames format) and its ground truth
	/// (groundTruthPrefixFor(rawlog_path) + "_ground_truth.txt" and
	/// "_ground_truth_robot_path.txt"), each atomically. Creates the folder.
	/// With wrong IDs or clutter (Scenario::hasOutliers()) also the true
	/// landmark of every measurement (MeasurementTruth.h).
	SimulationSummary writeRawlog(const std::string& rawlog_path) const;

	/// Odometry increment of the mid-point unicycle model: driving `distance_m`
	/// while turning by `angle_rad` moves the robot by
	/// (d cos(a/2), d sin(a/2), a) in its own frame.
	static Pose2 midpointIncrement(double distance_m, double angle_rad);

   private:
	/// Adds a twin to every grid feature (Scenario::cluster_pair_distance_m).
	void addClusterTwins();

	Scenario scenario_;
	std::vector<Eigen::Vector2d> features_;
	std::vector<LandmarkId> feature_ids_;  ///< parallel to features_
};

}  // namespace esif
