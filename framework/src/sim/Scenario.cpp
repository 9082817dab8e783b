#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/sim/Scenario.h>

#include <string>

namespace esif
{
void Scenario::declare(ParamBinder& b)
{
	b.integer("seed", seed, "seed of the simulator's random generators", Bounds::nonNegative());
	b.integer("steps", steps, "number of steps (scans), the first one at the start pose", Bounds::atLeast(1));
	b.real("dt_s", dt_s, "time between two steps [s]", Bounds::positive());

	b.real("world_size_m", world_size_m, "side of the square world [m]", Bounds::positive());
	b.integer(
		"features_per_side", features_per_side,
		"features form an n x n grid with a half-spacing margin to the sides", Bounds::atLeast(1));

	b.real("speed_mps", speed_mps, "constant true forward speed [m/s]", Bounds::positive());
	b.real("max_turn_rate_deg_s", max_turn_rate_deg_s, "bound on the true turn rate [deg/s]", Bounds::positive());
	b.real(
		"waypoint_margin_m", waypoint_margin_m,
		"waypoints are drawn uniformly inside the square shrunk by this margin [m]", Bounds::nonNegative());
	b.real("start_x_m", start_x_m, "start position from the bottom-left corner [m]", Bounds::any());
	b.real("start_y_m", start_y_m, "start position from the bottom-left corner [m]", Bounds::any());
	b.real("start_yaw_deg", start_yaw_deg, "start heading [deg]", Bounds::any());

	b.real("std_speed_mps", std_speed_mps, "odometry speed noise, 1 sigma [m/s]", Bounds::nonNegative());
	b.real(
		"std_turn_rate_deg_s", std_turn_rate_deg_s, "odometry turn-rate noise, 1 sigma [deg/s]",
		Bounds::nonNegative());

	b.real("sensor_max_range_m", sensor_max_range_m, "maximum sensing range [m]", Bounds::positive());
	b.real(
		"sensor_fov_deg", sensor_fov_deg, "full field of view centred on the sensor's x axis [deg]",
		Bounds{0, 360, true, false});
	b.real("std_range_m", std_range_m, "range noise, 1 sigma [m]", Bounds::nonNegative());
	b.real("std_bearing_deg", std_bearing_deg, "bearing noise, 1 sigma [deg]", Bounds::nonNegative());
	b.real("sensor_x_m", sensor_x_m, "sensor position on the robot [m]", Bounds::any());
	b.real("sensor_y_m", sensor_y_m, "sensor position on the robot [m]", Bounds::any());
	b.real("sensor_yaw_deg", sensor_yaw_deg, "sensor heading on the robot [deg]", Bounds::any());
}

void Scenario::validate() const
{
	const auto fail = [](const char* key, double value, const std::string& rule) {
		throw ConfigError(std::string("[simulation] ") + key + " = " + formatNumber(value) + ": " + rule);
	};
	const std::string square = "must be inside the square [0, world_size_m = " + formatNumber(world_size_m) + "]";
	if (start_x_m < 0 || start_x_m > world_size_m) fail("start_x_m", start_x_m, square);
	if (start_y_m < 0 || start_y_m > world_size_m) fail("start_y_m", start_y_m, square);
	// Waypoints need an area to be drawn from.
	if (2 * waypoint_margin_m >= world_size_m)
		fail(
			"waypoint_margin_m", waypoint_margin_m,
			"must be less than world_size_m / 2 = " + formatNumber(world_size_m / 2));
}

}  // namespace esif
