#pragma once
/// \file RunConfig.h
/// How every host command that runs a plugin reads its config (`esif run`
/// on a rawlog or on local maps, `esif localmaps build`, `esif compare`'s
/// check): the `[esif]` section, the plugin configured from its own
/// section, the rawlog read options, the side inputs the config names and
/// params.ini. One place, so the commands read a config exactly alike.

#include <esif/config/ConfigFile.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/RawlogReader.h>
#include <esif/loader/PluginLoader.h>
#include <esif/plugin/LocalMapJoiner.h>
#include <esif/run/HostParams.h>
#include <esif/safeio/OutputApart.h>

#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// Name of the host's own INI section.
constexpr const char* kHostSection = "esif";
/// File name of a run's data association (AssociationFile.h).
constexpr const char* kAssociationFileName = "associations.txt";

/// Reads and checks `[esif]`: `plugin` is required, `label` defaults to the
/// config file name, unknown keys are errors (ConfigError naming file and key).
HostParams loadHostParams(const ConfigFile& cfg);

/// Creates the plugin `[esif] plugin` names and configures it from its
/// section; any section other than `[esif]` and the plugin's is an error.
FilterPlugin::Ptr createConfiguredPlugin(const ConfigFile& cfg, const HostParams& host, PluginLoader& loader);

/// The plugin as a map-joining filter, or nullptr when it is not one.
LocalMapJoiner* asLocalMapJoiner(FilterPlugin& plugin);

/// The plugin as a map-joining filter; throws ConfigError "`config`: plugin
/// `name` cannot join local maps (--local-maps needs a local-map joining
/// plugin)" when it is not one.
LocalMapJoiner& requireLocalMapJoiner(FilterPlugin& plugin, const std::string& config, const std::string& name);

/// How the rawlog is turned into plugin input ([esif] hide_landmark_ids,
/// sensor-noise overrides, CObservationOdometry noise).
RawlogReadOptions readOptionsOf(const HostParams& host);

/// DIR/associations.txt of `host.associations_from`, checked before the
/// rawlog is read so that a wrong folder fails at once; nullopt when the
/// rawlog's own IDs are used. `from_command_line`: the folder came from
/// --associations-from (named so in the error) rather than the INI key.
std::optional<std::string> locateAssociations(const ConfigFile& cfg, const HostParams& host, bool from_command_line);

/// The rawlog's ground truth: PREFIX_ground_truth.txt (+ robot path) of
/// `prefix` when given (InputError when absent), else beside the rawlog
/// (nullopt when absent).
std::optional<GroundTruth> findGroundTruth(const std::optional<std::string>& prefix, const std::string& rawlog_path);

/// What a run on `rawlog` reads besides `config`, for requireOutputApart:
/// the rawlog, its ground-truth files (of `prefix`, else beside the
/// rawlog) and the associations folder the config or command line names.
std::vector<NamedInput> rawlogRunInputs(
	const std::string& config, const std::string& rawlog, const std::optional<std::string>& prefix,
	const std::optional<std::string>& associations_from);

/// The text of params.ini: `[esif]` and the plugin's section with every
/// effective value (defaults filled in).
std::string effectiveParamsIni(const HostParams& host, const FilterPlugin& plugin);

}  // namespace esif
