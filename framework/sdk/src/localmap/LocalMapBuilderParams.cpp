#include <esif/localmap/LocalMapBuilderParams.h>

namespace esif
{
void LocalMapBuilderParams::declare(ParamBinder& b)
{
	b.integer("local_map_steps", local_map_steps, "close a local map after this many steps; 0 = no step limit",
			  Bounds::nonNegative());
	b.integer("local_map_max_features", local_map_max_features,
			  "close a local map once it holds this many features; 0 = no limit", Bounds::nonNegative());
	b.real("local_map_max_distance_m", local_map_max_distance_m,
		   "close a local map once the robot travelled this far in it [m]; 0 = no limit", Bounds::nonNegative());
	b.integer("local_map_min_common_features", local_map_min_common_features,
			  "extend a local map until it holds this many features of the previous map, or of any earlier map "
			  "(local_map_common_features_in; Ch. 4 needs 2)",
			  Bounds::nonNegative());
	b.enumeration<CommonFeaturesIn>(
		"local_map_common_features_in", local_map_common_features_in,
		{{"previous_map", CommonFeaturesIn::PreviousMap}, {"earlier_maps", CommonFeaturesIn::EarlierMaps}},
		"where local_map_min_common_features are counted: in the previous map (the book's wording) or in any "
		"earlier map (the global map; by ID, the builder's own IDs count against the previous map)");
	b.enumeration<LocalMapLink>(
		"local_map_link", local_map_link,
		{{"shared_pose", LocalMapLink::SharedPose}, {"odometry", LocalMapLink::Odometry}},
		"next map starts at the previous end pose (shared_pose) or one step later, linked by that step's "
		"odometry (odometry, eq. 5.4)");
	b.real("local_map_global_features_radius_m", local_map_global_features_radius_m,
		   "associate each scan of a local map also with the global map's features within this distance of the "
		   "map's start [m], at least the sensor's range plus the distance one local map covers; a sighting of "
		   "one starts a local feature under its global ID, and the map level checks those IDs; 0 = off (a local "
		   "map knows only its own features, as in the book)",
		   Bounds::nonNegative());
	PrefixedBinder local(b, "local_");
	association.declare(local);
	local.enumeration<JacobianPoints>(
		"jacobians", jacobians,
		{{"current", JacobianPoints::Current}, {"first_estimates", JacobianPoints::FirstEstimates}},
		"where the local map's EKF takes its Jacobians: current = at the latest estimate (textbook EKF); "
		"first_estimates = at the robot's prior and each feature's first estimate (Huang et al.'s FEJ)");
}

}  // namespace esif
