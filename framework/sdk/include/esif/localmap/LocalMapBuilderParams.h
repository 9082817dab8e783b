#pragma once
/// \file LocalMapBuilderParams.h
/// When the local-map builder closes a map and how it associates inside one
/// (book Sec. 4.4.4 and Sec. 5 intro). Declared inside the section of the
/// joining plugin that builds its own local maps; `esif localmaps build`
/// reads them from the same section, so the files it writes are the maps
/// that plugin would fuse.
///
/// A map is closed after the step at which any of the limits set (> 0) is
/// reached, but only once it holds at least local_map_min_common_features
/// features of the previous map, or of any earlier map (the Ch. 4 rule;
/// 0 for SLSJF). With every
/// limit 0 the whole log is one local map. The last, partial map is closed
/// at the end of the log whatever the rules say.

#include <esif/config/ParamBinder.h>
#include <esif/ekf/EkfAssociationParams.h>
#include <esif/ekf/EkfSlamCore.h>

namespace esif
{
/// Which maps the common features of the Ch. 4 rule are counted in.
enum class CommonFeaturesIn
{
	/// The previous map (the book's wording, Sec. 4.4.4).
	PreviousMap,
	/// Any earlier map: what the joining needs, two features the global map
	/// holds (the authors' Victoria Park maps meet it this way). Where the
	/// robot leaves the previous map's features behind quickly, the
	/// previous-map rule stretches maps over hundreds of steps. Counted by
	/// ID: maps whose features the builder numbered itself fall back to the
	/// previous map.
	EarlierMaps
};

/// How the next local map starts.
enum class LocalMapLink
{
	SharedPose,	 ///< at the previous map's end pose: start(k+1) = end(k), as in the book and the authors' data
	Odometry	 ///< one step later: the odometry of that step links end(k) to start(k+1) (eq. 5.4)
};

struct LocalMapBuilderParams
{
	int local_map_steps = 45;  ///< close after this many steps; 0 = no step limit (Sec. 5.5: 18005 / 400)
	int local_map_max_features = 0;	 ///< close once the map holds this many features; 0 = no limit
	double local_map_max_distance_m = 0;  ///< close once the robot travelled this far in the map [m]; 0 = no limit
	/// Close only once the map holds this many features of the previous map
	/// (0 for SLSJF; 2 for D-SLAM map joining, Sec. 4.4.4).
	int local_map_min_common_features = 0;
	CommonFeaturesIn local_map_common_features_in = CommonFeaturesIn::PreviousMap;	///< previous_map | earlier_maps
	LocalMapLink local_map_link = LocalMapLink::SharedPose;	 ///< shared_pose | odometry
	/// A joining filter that can (SLSJF, D-SLAM map joining) gives each new
	/// local map the global map's features within this distance of the map's
	/// start [m], and each scan is associated with them too: a sighting of a
	/// mapped feature then starts a local feature under its global ID, with
	/// the per-scan waits of the EKF, and the map level checks those IDs.
	/// At least the sensor's range plus the distance one local map covers: a
	/// feature the map sees but was not given is associated at the map level
	/// only, and one near the edge can be mistaken for a given neighbour.
	/// 0 = off: a local map knows only its own features (the book).
	double local_map_global_features_radius_m = 0;
	/// Association inside a local map (keys prefixed `local_`, e.g. local_association).
	EkfAssociationParams association;
	/// Where the local map's EKF takes its Jacobians (key local_jacobians):
	/// Current (the textbook EKF) or FirstEstimates (EkfSlamCore.h).
	JacobianPoints jacobians = JacobianPoints::Current;

	void declare(ParamBinder& b);
};

}  // namespace esif
