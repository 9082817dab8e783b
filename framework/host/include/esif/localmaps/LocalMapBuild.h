#pragma once
/// \file LocalMapBuild.h
/// `esif localmaps build`: the local maps a joining plugin would fuse, built
/// from a rawlog with that plugin's builder parameters and written in the
/// authors' folder format (LocalMapFiles.h), with the ground truth in
/// local-map form when the rawlog has it. The folder can then be given to
/// `esif run --local-maps`, to other joining plugins, or to the authors' tools.

#include <esif/formats/GroundTruth.h>
#include <esif/formats/LocalMapFiles.h>
#include <esif/formats/RawlogReader.h>
#include <esif/localmap/LocalMapBuilderParams.h>
#include <esif/loader/PluginLoader.h>

#include <optional>
#include <string>
#include <vector>

namespace esif
{
struct LocalMapBuildRequest
{
	std::string config_path;  ///< `[esif] plugin` must be a local-map joining plugin
	std::string rawlog_path;
	/// Ground-truth prefix; when empty, PREFIX is looked for beside the rawlog.
	std::optional<std::string> ground_truth_prefix;
	std::string out_dir;
	bool progress_bar = true;
};

/// writeLocalMapFiles into `dir` as one all-or-nothing output folder
/// (RunFolder.h: locked, written aside, swapped into place; a folder esif
/// did not write, or one holding files it did not write, is refused).
void writeLocalMapFolder(const LocalMapFolder& folder, const std::string& dir);

/// Every step of `log` through a LocalMapBuilder with `params`; the maps in
/// order, the last (partial) one included. NumericalError names the rawlog.
std::vector<LocalMap> buildLocalMaps(const Rawlog& log, const LocalMapBuilderParams& params, bool progress_bar);

/// The authors' format keeps IDs <= 0 for poses: when a feature ID of
/// `maps` is not positive (MRPT's simulated landmarks are numbered from 0),
/// adds 1 - (smallest ID) to every feature ID, in the maps' features and
/// their step reports alike, and returns that offset (0: nothing changed).
LandmarkId makeFeatureIdsPositive(std::vector<LocalMap>& maps);

/// The ground truth in local-map form (`truth` already in the frame of the
/// initial pose, which is pose 0 of the maps): each feature ID of the maps
/// with the position of the true landmark it stands for, and the true pose
/// at each map's last step as its end pose. A feature stands for the true
/// landmark most of its measurements carried (AssociationAudit's majority
/// vote over the maps' step reports and `log.true_ids`): the identity when
/// the builder used the rawlog's IDs, the right landmark when they were
/// hidden from it. Features of no known true landmark, and maps whose last
/// step is beyond the true path, are left out.
void attachLocalMapGroundTruth(LocalMapFolder& folder, const Rawlog& log, const GroundTruth& truth);

/// What `esif localmaps build` wrote.
struct LocalMapBuildResult
{
	LocalMapFolder folder;
	LandmarkId id_offset = 0;  ///< added to the rawlog's IDs (makeFeatureIdsPositive)
};

/// The maps of a build, before anything is written.
struct LocalMapsOfRawlog
{
	Rawlog log;	 ///< as read (with the config's read options and associations)
	std::vector<LocalMap> maps;	 ///< IDs made positive
	LandmarkId id_offset = 0;
	std::optional<GroundTruth> truth;  ///< the rawlog's, in the frame of the initial pose
	/// The config's plugin, configured, whose builder parameters built the
	/// maps; it has joined none of them (a LocalMapJoiner).
	FilterPlugin::Ptr plugin;
};

/// The reading and building half of runLocalMapBuild (same checks, same
/// order), for commands that use the maps without writing them.
LocalMapsOfRawlog buildLocalMapsOfRawlog(const LocalMapBuildRequest& request, PluginLoader& loader);

/// The whole command: reads the config (its plugin must be a LocalMapJoiner,
/// else ConfigError "`config`: plugin X is not a local-map joining plugin"),
/// configures the plugin from its section as `esif run` does, reads the
/// rawlog with the `[esif]` read options (hide_landmark_ids, sensor-noise
/// overrides, associations_from), builds the maps with the plugin's
/// localMapBuilderParams(), makes their IDs positive, attaches the ground
/// truth and writes them with writeLocalMapFolder. Config errors are found
/// before the rawlog is read. Returns what was written.
LocalMapBuildResult runLocalMapBuild(const LocalMapBuildRequest& request, PluginLoader& loader);

}  // namespace esif
