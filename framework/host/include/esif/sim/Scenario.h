#pragma once
/// \file Scenario.h
/// Parameters of a simulated range-bearing SLAM experiment, read from the INI
/// section [simulation]. The defaults reproduce the book's noise levels
/// (Pioneer-like odometry, laser-like sensor: Sec. 1.3.3): range 0.1 m,
/// bearing 1 deg, speed 0.02 m/s, turn rate 3 deg/s.
///
/// World frame: the square [0, world_size_m] x [0, world_size_m], origin at
/// its bottom-left corner, x to the right, y up.

#include <esif/core/StepInput.h>

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace esif
{
class ConfigFile;
class ParamBinder;

struct Scenario
{
	// ---- random stream and length
	int seed = 1;  ///< seed of the simulator's random generators; >= 0
	/// Seed of the noise alone (odometry and sensor noise, wrong IDs,
	/// clutter); -1 (default): derived from `seed`, as before the key existed.
	/// The path (waypoints) and the layout (twins) follow `seed` only, so a
	/// Monte Carlo campaign varies noise_seed to draw new noise on the same
	/// world and path; >= -1
	int noise_seed = -1;
	int steps = 3000;  ///< number of rawlog steps (scans), including the first one at the start pose; >= 1
	double dt_s = 0.1;	///< time between two steps [s]; > 0

	// ---- environment
	double world_size_m = 40.0;	 ///< side of the square world [m]; > 0
	/// Features form an n x n grid, uniformly spaced rows and columns with a
	/// half-spacing margin to the square's sides; >= 1
	int features_per_side = 14;
	/// A featureless band across the world, for the scans that see fewer than
	/// two mapped features (book Sec. 3.4.1, admissible measurements): grid
	/// features with featureless_x_min_m <= x <= featureless_x_max_m are
	/// removed. The band is off when both are equal (default: both 0);
	/// featureless_x_min_m > featureless_x_max_m is an error. Removed features
	/// leave their IDs unused [m]
	double featureless_x_min_m = 0.0;
	double featureless_x_max_m = 0.0;  ///< see featureless_x_min_m [m]

	// ---- robot motion (the true controls)
	double speed_mps = 1.0;	 ///< constant true forward speed [m/s]; > 0
	double max_turn_rate_deg_s = 30.0;	///< bound on the true turn rate [deg/s]; > 0
	/// Waypoints are drawn uniformly inside the square shrunk by this margin
	/// [m]; >= 0. The robot may overshoot that area by up to a turning radius
	/// (speed_mps / max turn rate) while turning towards the next waypoint.
	double waypoint_margin_m = 5.0;
	/// Scripted tour instead of random waypoints: "x1 y1; x2 y2; ..." in the
	/// world frame [m], visited in order, then again from the first, for as
	/// long as the steps last. Empty (default): the random tour. At least two
	/// waypoints, each inside the square, each at least minWaypointSpacing()
	/// from the one before it (the first from the start, the first from the
	/// last) so the robot can always reach it; waypoint_margin_m is then unused.
	std::string waypoints;
	double start_x_m = 1.0;	 ///< start position, from the bottom-left corner [m]
	double start_y_m = 1.0;	 ///< start position, from the bottom-left corner [m]
	double start_yaw_deg = 45.0;  ///< start heading [deg] (45 = towards the square's centre)

	// ---- odometry noise (1 sigma, added to the speed and turn-rate readings)
	double std_speed_mps = 0.02;  ///< [m/s]; >= 0
	double std_turn_rate_deg_s = 3.0;  ///< [deg/s]; >= 0

	// ---- range-bearing sensor
	double sensor_max_range_m = 5.0;  ///< features farther than this are not seen [m]; > 0
	double sensor_fov_deg = 180.0;	///< full field of view, centred on the sensor's x axis [deg]; in (0, 360]
	double std_range_m = 0.1;  ///< range noise, 1 sigma [m]; >= 0
	double std_bearing_deg = 1.0;  ///< bearing noise, 1 sigma [deg]; >= 0
	double sensor_x_m = 0.0;  ///< sensor pose on the robot [m]
	double sensor_y_m = 0.0;  ///< sensor pose on the robot [m]
	double sensor_yaw_deg = 0.0;  ///< sensor pose on the robot [deg]

	// ---- outliers and hard layouts (all off by default: the rawlog is then
	// byte-identical to one made before these keys existed)
	/// Probability that a measurement carries the ID of another landmark (a
	/// misread, drawn independently per measurement): one of the 8 landmarks
	/// nearest to the true one that are not measured in the same scan (a
	/// scan cannot hold one ID twice), drawn uniformly; in [0, 1]. The true
	/// IDs go to PREFIX_ground_truth_measurement_ids.txt.
	double wrong_id_rate = 0.0;
	/// Expected number of spurious returns (clutter) per scan, Poisson:
	/// uniform over the area within sensor_max_range_m and the field of
	/// view, each with a fresh ID no landmark has (from clutterIdBase(),
	/// counting up), so ground truth knows none of them; in [0, 100].
	double spurious_rate = 0.0;
	/// > 0: every grid feature gets a twin at this distance in a uniformly
	/// random direction, ID = its own + features_per_side^2 (the pair is then
	/// two landmarks, a hard case for data association); 0: no twins [m].
	/// Must be below featureSpacing() / 2 so each twin is nearer to its own
	/// feature than to any other grid feature.
	double cluster_pair_distance_m = 0.0;

	/// Declares every field once, for loading (`loadParams(scenario,
	/// section)`), validation of each value and listings.
	void declare(ParamBinder& b);

	/// The [simulation] section of `config`; throws ConfigError naming the
	/// file and key for a bad value or an unknown key, and naming the file
	/// when checkSections() fails. Cross-field rules are left to validate().
	static Scenario fromConfig(const ConfigFile& config);

	/// Throws ConfigError naming the file unless `config` has a [simulation]
	/// section and no other: a misspelt section, an empty file or a filter
	/// config would otherwise simulate the default world.
	static void checkSections(const ConfigFile& config);

	/// Checks the rules that involve several fields (the start inside the
	/// square, a non-empty waypoint area, an ordered featureless band), the
	/// size caps (kMaxLandmarks landmarks, kMaxMeasurements expected
	/// measurements) and the waypoint list (see `waypoints`); throws
	/// ConfigError naming the [simulation] keys at fault. Per-field rules are
	/// checked by declare().
	void validate() const;

	/// Landmarks of the world: grid features outside the featureless band,
	/// and their twins.
	std::size_t landmarkCount() const;

	/// Expected measurements of one scan, for the size check before anything
	/// is allocated: the landmarks in the sensor's footprint (a sector of
	/// sensor_max_range_m and sensor_fov_deg) at the world's mean landmark
	/// density, at most all of them, plus spurious_rate.
	double expectedMeasurementsPerScan() const;

	/// The seed of the noise and outlier generators: noise_seed when set
	/// (>= 0), else `seed`.
	std::uint32_t effectiveNoiseSeed() const
	{
		return static_cast<std::uint32_t>(noise_seed >= 0 ? noise_seed : seed);
	}

	/// Whether grid features have twins (cluster_pair_distance_m > 0).
	bool hasClusterPairs() const { return cluster_pair_distance_m > 0; }

	/// Whether any measurement may carry an ID other than its landmark's
	/// (wrong IDs or clutter): the rawlog's IDs are then not the truth.
	bool hasOutliers() const { return wrong_id_rate > 0 || spurious_rate > 0; }

	/// First ID of clutter returns: above every landmark ID (grid and twins).
	LandmarkId clutterIdBase() const
	{
		const LandmarkId grid = LandmarkId(features_per_side) * features_per_side;
		return hasClusterPairs() ? 2 * grid : grid;
	}

	/// Spacing between two neighbouring features [m].
	double featureSpacing() const { return world_size_m / features_per_side; }

	/// Whether the featureless band is on (featureless_x_min_m < featureless_x_max_m).
	bool hasFeaturelessBand() const { return featureless_x_min_m < featureless_x_max_m; }

	/// Whether a feature at world abscissa `x_m` lies in the featureless band.
	bool inFeaturelessBand(double x_m) const
	{
		return hasFeaturelessBand() && x_m >= featureless_x_min_m && x_m <= featureless_x_max_m;
	}

	/// The scripted waypoints parsed from `waypoints` (empty: random tour);
	/// throws ConfigError naming the key when the text is malformed. The
	/// rules on their positions are checked by validate().
	std::vector<Eigen::Vector2d> scriptedWaypoints() const;

	/// Least distance between consecutive scripted waypoints [m]: a turning
	/// diameter (2 speed_mps / max turn rate), plus twice the distance at
	/// which a waypoint counts as reached, so that the next waypoint lies
	/// outside both minimum turning circles of the robot wherever it reaches
	/// the previous one.
	double minWaypointSpacing() const;

	/// The robot switches to its next waypoint once this close to the
	/// current one [m].
	static constexpr double kWaypointReach_m = 1.0;

	/// Upper bound of spurious_rate: more clutter per scan than a grid scan
	/// has true returns by an order of magnitude is no longer a SLAM problem.
	static constexpr double kMaxSpuriousRate = 100.0;

	// ---- size bounds, checked before anything is allocated. The committed
	// scenarios are far inside them (at most 35,188 steps, 10,000 landmarks
	// and 236,000 expected measurements, booksim); beyond them a scenario is
	// a typo (features_per_side = 1e6 asked for 1e12 landmarks and ended in
	// std::bad_alloc) or more than any filter here could replay. Rawlog
	// sizes measured on grid196 and booksim_2000 before compression: 458
	// bytes a step plus 16 a measurement.

	/// A million landmarks: every simulated step tests each for visibility,
	/// and the filters' states grow with them (an EKF of 1e6 landmarks would
	/// hold a 2e6 x 2e6 covariance, 32 TB).
	static constexpr std::size_t kMaxLandmarks = 1'000'000;
	/// So that the grid alone stays within kMaxLandmarks.
	static constexpr double kMaxFeaturesPerSide = 1000;
	/// Ten million measurements, 42 times booksim's: 160 MB of rawlog, and
	/// 640 MB once a replay holds them in memory (64 bytes each with their
	/// covariance).
	static constexpr double kMaxMeasurements = 1e7;
	/// A million steps: 28 hours of driving at dt_s = 0.1, 28 times booksim's;
	/// 0.46 GB of rawlog records, and the true path kept in memory.
	static constexpr double kMaxSteps = 1e6;
	/// One minute between scans: the motion model holds the controls
	/// constant over a step, which says nothing about a longer interval.
	static constexpr double kMaxDt_s = 60.0;
	/// A 100 km square: beyond any scenario of the book (300 m at most);
	/// larger values are unit mistakes (millimetres for metres).
	static constexpr double kMaxWorldSize_m = 1e5;
	/// 100 m/s (360 km/h): no ground robot; also the bound of its noise.
	static constexpr double kMaxSpeed_mps = 100.0;
	/// Ten turns a second; also the bound of its noise.
	static constexpr double kMaxTurnRate_deg_s = 3600.0;
	/// A kilometre: beyond any range sensor the book models (an 80 m laser);
	/// also the bound of the range noise, which beyond it drowns every range.
	static constexpr double kMaxSensorRange_m = 1000.0;

   private:
	/// The landmark and measurement caps (validate()).
	void validateSize() const;
};

}  // namespace esif
