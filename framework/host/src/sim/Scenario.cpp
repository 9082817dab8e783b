#include <esif/config/ConfigFile.h>
#include <esif/config/ConfigSection.h>
#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/core/NumberToken.h>
#include <esif/core/TextInput.h>
#include <esif/sim/Scenario.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

namespace esif
{
void Scenario::declare(ParamBinder& b)
{
	b.integer("seed", seed, "seed of the simulator's random generators", Bounds::nonNegative());
	b.integer(
		"noise_seed", noise_seed,
		"seed of the odometry and sensor noise (and wrong IDs, clutter) alone; -1: from seed. The path and "
		"the layout follow seed only (esif montecarlo varies noise_seed)",
		Bounds::atLeast(-1));
	b.integer(
		"steps", steps, "number of steps (scans), the first one at the start pose",
		Bounds::closed(1, kMaxSteps));
	b.real("dt_s", dt_s, "time between two steps [s]", Bounds{0, kMaxDt_s, true, false});

	b.real("world_size_m", world_size_m, "side of the square world [m]", Bounds{0, kMaxWorldSize_m, true, false});
	b.integer(
		"features_per_side", features_per_side,
		"features form an n x n grid with a half-spacing margin to the sides", Bounds::closed(1, kMaxFeaturesPerSide));
	b.real(
		"featureless_x_min_m", featureless_x_min_m,
		"grid features with featureless_x_min_m <= x <= featureless_x_max_m are removed; off when both are "
		"equal [m]",
		Bounds::any());
	b.real(
		"featureless_x_max_m", featureless_x_max_m,
		"upper end of the featureless band; must be >= featureless_x_min_m [m]", Bounds::any());

	b.real("speed_mps", speed_mps, "constant true forward speed [m/s]", Bounds{0, kMaxSpeed_mps, true, false});
	b.real(
		"max_turn_rate_deg_s", max_turn_rate_deg_s, "bound on the true turn rate [deg/s]",
		Bounds{0, kMaxTurnRate_deg_s, true, false});
	b.real(
		"waypoint_margin_m", waypoint_margin_m,
		"waypoints are drawn uniformly inside the square shrunk by this margin [m]", Bounds::nonNegative());
	b.text(
		"waypoints", waypoints,
		"scripted tour \"x1 y1; x2 y2; ...\" [m], visited in order and repeated; empty: random waypoints");
	b.real("start_x_m", start_x_m, "start position from the bottom-left corner [m]", Bounds::any());
	b.real("start_y_m", start_y_m, "start position from the bottom-left corner [m]", Bounds::any());
	b.real("start_yaw_deg", start_yaw_deg, "start heading [deg]", Bounds::any());

	b.real(
		"std_speed_mps", std_speed_mps, "odometry speed noise, 1 sigma [m/s]", Bounds::closed(0, kMaxSpeed_mps));
	b.real(
		"std_turn_rate_deg_s", std_turn_rate_deg_s, "odometry turn-rate noise, 1 sigma [deg/s]",
		Bounds::closed(0, kMaxTurnRate_deg_s));

	b.real(
		"sensor_max_range_m", sensor_max_range_m, "maximum sensing range [m]",
		Bounds{0, kMaxSensorRange_m, true, false});
	b.real(
		"sensor_fov_deg", sensor_fov_deg, "full field of view centred on the sensor's x axis [deg]",
		Bounds{0, 360, true, false});
	b.real("std_range_m", std_range_m, "range noise, 1 sigma [m]", Bounds::closed(0, kMaxSensorRange_m));
	b.real("std_bearing_deg", std_bearing_deg, "bearing noise, 1 sigma [deg]", Bounds::closed(0, 180));
	b.real("sensor_x_m", sensor_x_m, "sensor position on the robot [m]", Bounds::any());
	b.real("sensor_y_m", sensor_y_m, "sensor position on the robot [m]", Bounds::any());
	b.real("sensor_yaw_deg", sensor_yaw_deg, "sensor heading on the robot [deg]", Bounds::any());

	b.real(
		"wrong_id_rate", wrong_id_rate,
		"probability that a measurement carries the ID of another landmark (one of the 8 nearest to it not "
		"measured in the same scan); 0 = none",
		Bounds::closed(0, 1));
	b.real(
		"spurious_rate", spurious_rate,
		"expected spurious returns per scan (Poisson), uniform in range and field of view, each with a fresh ID "
		"no landmark has; 0 = none",
		Bounds::closed(0, kMaxSpuriousRate));
	b.real(
		"cluster_pair_distance_m", cluster_pair_distance_m,
		"> 0: every grid feature gets a twin this far away in a random direction (ID + features_per_side^2); "
		"below half the feature spacing [m]",
		Bounds::nonNegative());
}

void Scenario::checkSections(const ConfigFile& config)
{
	for (const auto& name : config.sectionNames())
		if (name != "simulation")
			throw ConfigError(
				config.origin() + ": " + (name.empty() ? "keys before any section" : "[" + name + "]: unknown section") +
				" (a scenario has only [simulation])");
	if (!config.hasSection("simulation"))
		throw ConfigError(config.origin() + ": no [simulation] section (not a scenario file)");
}

Scenario Scenario::fromConfig(const ConfigFile& config)
{
	checkSections(config);
	const ConfigSection section = config.section("simulation");
	Scenario scenario;
	loadParams(scenario, section);
	section.rejectUnknownKeys();
	return scenario;
}

void Scenario::validate() const
{
	const auto fail = [](const char* key, double value, const std::string& rule) {
		throw ConfigError(std::string("[simulation] ") + key + " = " + formatNumber(value) + ": " + rule);
	};
	const std::string square = "must be inside the square [0, world_size_m = " + formatNumber(world_size_m) + "]";
	if (start_x_m < 0 || start_x_m > world_size_m) fail("start_x_m", start_x_m, square);
	if (start_y_m < 0 || start_y_m > world_size_m) fail("start_y_m", start_y_m, square);
	if (featureless_x_min_m > featureless_x_max_m)
		fail(
			"featureless_x_min_m", featureless_x_min_m,
			"must be <= featureless_x_max_m = " + formatNumber(featureless_x_max_m) +
				" (equal values: no featureless band)");

	if (cluster_pair_distance_m >= featureSpacing() / 2)
		fail(
			"cluster_pair_distance_m", cluster_pair_distance_m,
			"must be less than half the feature spacing (world_size_m / features_per_side / 2 = " +
				formatNumber(featureSpacing() / 2) + ") so each twin is nearest to its own feature");

	validateSize();

	const std::vector<Eigen::Vector2d> script = scriptedWaypoints();
	if (script.empty())
	{
		// Random waypoints need an area to be drawn from.
		if (2 * waypoint_margin_m >= world_size_m)
			fail(
				"waypoint_margin_m", waypoint_margin_m,
				"must be less than world_size_m / 2 = " + formatNumber(world_size_m / 2));
		return;
	}
	const auto failWaypoints = [&](const std::string& rule) {
		throw ConfigError("[simulation] waypoints = " + waypoints + ": " + rule);
	};
	const auto point = [](const Eigen::Vector2d& p) {
		return "(" + formatNumber(p.x()) + ", " + formatNumber(p.y()) + ")";
	};
	if (script.size() < 2) failWaypoints("needs at least two waypoints (\"x1 y1; x2 y2; ...\")");
	const double spacing = minWaypointSpacing();
	const Eigen::Vector2d start(start_x_m, start_y_m);
	for (std::size_t i = 0; i < script.size(); ++i)
	{
		const Eigen::Vector2d& p = script[i];
		const std::string name = "waypoint " + std::to_string(i + 1) + " " + point(p);
		if (p.x() < 0 || p.x() > world_size_m || p.y() < 0 || p.y() > world_size_m)
			failWaypoints(name + " " + square);
		// The leg into waypoint i starts at the previous waypoint (the last
		// one for the first, when the tour repeats) and, the first time, at
		// the start.
		const Eigen::Vector2d& previous = script[i == 0 ? script.size() - 1 : i - 1];
		const std::string rule = ": must be at least " + formatNumber(spacing) +
			" m (2 speed_mps / max_turn_rate_deg_s in rad/s, plus 2 m) so the robot can reach it";
		if ((p - previous).norm() < spacing)
			failWaypoints(
				name + " is " + formatNumber((p - previous).norm()) + " m from the waypoint before it " +
				point(previous) + rule);
		if (i == 0 && (p - start).norm() < spacing)
			failWaypoints(name + " is " + formatNumber((p - start).norm()) + " m from the start" + rule);
	}
}

std::size_t Scenario::landmarkCount() const
{
	std::size_t columns = 0;  // grid columns outside the featureless band
	for (int col = 0; col < features_per_side; ++col) columns += !inFeaturelessBand((col + 0.5) * featureSpacing());
	const std::size_t grid = columns * static_cast<std::size_t>(features_per_side);
	return hasClusterPairs() ? 2 * grid : grid;
}

double Scenario::expectedMeasurementsPerScan() const
{
	const double landmarks = static_cast<double>(landmarkCount());
	const double footprint_m2 = sensor_fov_deg / 360.0 * M_PI * sensor_max_range_m * sensor_max_range_m;
	const double seen = std::min(landmarks, landmarks / (world_size_m * world_size_m) * footprint_m2);
	return seen + spurious_rate;
}

void Scenario::validateSize() const
{
	const auto fail = [](const std::string& keys, const std::string& rule) {
		throw ConfigError("[simulation] " + keys + ": " + rule);
	};
	const std::size_t landmarks = landmarkCount();
	if (landmarks > kMaxLandmarks)
		fail(
			"features_per_side = " + std::to_string(features_per_side) +
				", cluster_pair_distance_m = " + formatNumber(cluster_pair_distance_m),
			std::to_string(landmarks) + " landmarks (grid features and their twins), above the cap of " +
				std::to_string(kMaxLandmarks));
	const double per_scan = expectedMeasurementsPerScan();
	const double measurements = per_scan * steps;
	if (measurements > kMaxMeasurements)
	{
		char figures[160];
		std::snprintf(
			figures, sizeof(figures), "about %.3g measurements expected (%.4g per scan x %d steps), above the cap of %.0f",
			measurements, per_scan, steps, kMaxMeasurements);
		fail(
			"steps = " + std::to_string(steps) + ", features_per_side = " + std::to_string(features_per_side) +
				", sensor_max_range_m = " + formatNumber(sensor_max_range_m),
			std::string(figures) +
				" (per scan: the landmarks within sensor_max_range_m and sensor_fov_deg at the grid's density, plus "
				"spurious_rate)");
	}
}

std::vector<Eigen::Vector2d> Scenario::scriptedWaypoints() const
{
	std::vector<Eigen::Vector2d> out;
	const auto blank = [](const std::string& t) { return t.find_first_not_of(" \t\r\n") == std::string::npos; };
	if (blank(waypoints)) return out;
	std::size_t begin = 0;
	for (int index = 1;; ++index)
	{
		const std::size_t end = waypoints.find(';', begin);
		const std::string item = waypoints.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
		const std::vector<std::string> words = whitespaceTokens(item);
		std::optional<double> x, y;
		if (words.size() == 2)
			x = doubleToken(words[0], NonFinite::rejected), y = doubleToken(words[1], NonFinite::rejected);
		if (!x || !y)
		{
			std::string joined;
			for (const auto& w : words) joined += (joined.empty() ? "" : " ") + w;
			throw ConfigError(
				"[simulation] waypoints = " + waypoints + ": waypoint " + std::to_string(index) + " '" + joined +
				"' must be two numbers 'x y' [m]; waypoints are separated by ';'");
		}
		out.emplace_back(*x, *y);
		if (end == std::string::npos) break;
		begin = end + 1;
	}
	return out;
}

double Scenario::minWaypointSpacing() const
{
	const double turning_radius_m = speed_mps / (max_turn_rate_deg_s * M_PI / 180.0);
	return 2 * turning_radius_m + 2 * kWaypointReach_m;
}

}  // namespace esif
