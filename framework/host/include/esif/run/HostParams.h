#pragma once
/// \file HostParams.h
/// The host's own INI section `[esif]`: which plugin to run and how the host
/// turns the rawlog into plugin input and outputs.

#include <esif/calibration/NoiseCalibration.h>
#include <esif/config/ParamBinder.h>

#include <string>

namespace esif
{
struct HostParams
{
	std::string plugin;	 ///< plugin class name, e.g. EkfSlam (required)
	std::string label;	///< name of the run in comparisons; default: config file name
	bool hide_landmark_ids = false;	 ///< strip landmark IDs from the plugin's input (scored still)
	double sensor_std_range_m = 0;	///< override of the rawlog's range noise; 0 = use the rawlog's
	double sensor_std_bearing_deg = 0;	///< override of the rawlog's bearing noise; 0 = use the rawlog's
	double odometry_obs_std_xy_m = 0.05;  ///< per-step noise of CObservationOdometry increments
	double odometry_obs_std_phi_deg = 1.0;	///< per-step heading noise of CObservationOdometry increments
	double keyframe_min_distance_m = 0;	 ///< map.simplemap keeps a scan every this many metres; 0 = all
	int image_size_px = 1000;  ///< map.png size
	int max_measurements_per_scan = 1000;  ///< a scan with more is refused as corrupt or hostile input
	/// Run folder whose associations.txt replaces the rawlog's landmark IDs
	/// (relative to the current directory; in `esif compare` also the label of
	/// another compared config); empty = the rawlog's own IDs.
	std::string associations_from;
	/// Run folder (trajectory.tum, landmarks.txt) whose estimate starts a
	/// plugin that takes one (FilterPlugin::usesInitialEstimate), relative to
	/// the current directory; empty = none.
	std::string initial_run;
	/// Calibration file (NoiseCalibration.h, written by `esif calibrate`),
	/// relative to the config's folder; empty = the rawlog's noise as it is.
	std::string calibration;
	/// Its values, loaded by loadHostParams (not a key of [esif]).
	NoiseCalibration noise;

	void declare(ParamBinder& b)
	{
		b.text("plugin", plugin, "filter plugin class name (see `esif plugins`)");
		b.text("label", label, "name of this run in comparison tables (default: config file name)");
		b.flag("hide_landmark_ids", hide_landmark_ids,
			   "hide the rawlog's landmark IDs from the plugin (it must associate itself; IDs still score it)");
		b.real("sensor_std_range_m", sensor_std_range_m, "range noise 1-sigma [m], 0 = from the rawlog",
			   Bounds::nonNegative());
		b.real("sensor_std_bearing_deg", sensor_std_bearing_deg, "bearing noise 1-sigma [deg], 0 = from the rawlog",
			   Bounds::nonNegative());
		b.real("odometry_obs_std_xy_m", odometry_obs_std_xy_m, "x/y noise per CObservationOdometry step [m]",
			   Bounds::positive());
		b.real("odometry_obs_std_phi_deg", odometry_obs_std_phi_deg,
			   "heading noise per CObservationOdometry step [deg]", Bounds::positive());
		b.real("keyframe_min_distance_m", keyframe_min_distance_m,
			   "distance between keyframes of map.simplemap [m], 0 = every scan", Bounds::nonNegative());
		b.integer("max_measurements_per_scan", max_measurements_per_scan,
				  "a rawlog scan with more range-bearing measurements is refused (a corrupt or hostile file)",
				  Bounds::closed(1, 1000000));
		b.integer("image_size_px", image_size_px, "map.png width and height [px]", Bounds::closed(200, 8000));
		b.text("associations_from", associations_from,
			   "run folder whose associations.txt gives the landmark IDs of every measurement (in esif compare "
			   "also another config's label); empty = the rawlog's IDs");
		b.text("initial_run", initial_run,
			   "run folder (trajectory.tum, landmarks.txt) whose estimate the plugin starts from, for plugins "
			   "that take one (the full-SLAM baseline); empty = none");
		b.text("calibration", calibration,
			   "calibration file of the rawlog's noise (esif calibrate), relative to this config's folder; empty = "
			   "the rawlog's noise");
	}
};

}  // namespace esif
