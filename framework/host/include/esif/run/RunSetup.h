#pragma once
/// \file RunSetup.h
/// The steps every host command that runs a plugin shares (`esif run` on a
/// rawlog or on local maps, `esif localmaps build`): the `[esif]` section,
/// the plugin configured from its own section, the rawlog read options, the
/// associations folder, params.ini and the run's common stats keys. One
/// place, so the commands read a config exactly alike.

#include <esif/config/ConfigFile.h>
#include <esif/eval/AssociationAudit.h>
#include <esif/eval/Evaluator.h>
#include <esif/eval/StateNees.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/RawlogReader.h>
#include <esif/formats/StatsJson.h>
#include <esif/plugin/LocalMapJoiner.h>
#include <esif/run/HostParams.h>
#include <esif/run/PluginLoader.h>
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

/// Marks `stats` suspect or not (SuspectResult.h) and says why on stderr
/// in one warning line when it is.
void flagSuspectResult(Stats& stats);

/// The text of params.ini: `[esif]` and the plugin's section with every
/// effective value (defaults filled in).
std::string effectiveParamsIni(const HostParams& host, const FilterPlugin& plugin);

/// Nearest-rank percentile: the smallest value with at least `p` of the
/// data at or below it; 0 for no data.
double nearestRankPercentile(std::vector<double> values, double p);

/// Peak resident memory of this process [MB].
double peakRssMb();

/// Sets KEY_mean, KEY_p50, KEY_p99 and KEY_max of `us` (0 for no data).
void setTimeStats(Stats& stats, const std::string& key, const std::vector<double>& us);

/// Sets state_dim, poses_in_state and info_nnz (null for covariance-form plugins).
void setCostStats(Stats& stats, const CostFigures& cost);

/// Sets da_new, da_matched, da_rejected, da_wrong (null without true IDs),
/// da_id_given and da_id_rejected (null on local maps).
void setAssociationStats(Stats& stats, const AssociationAudit& audit);

/// Sets the accuracy keys (landmark_rmse_m, ate_rmse_m, NEES means,
/// consistent fractions, landmarks_evaluated); null without ground truth.
void setAccuracyStats(Stats& stats, const std::optional<Accuracy>& accuracy);

/// The whole-state NEES of the plugin's final state against `reference`
/// (eval/StateNees.h), its landmarks paired through `filter_to_reference`;
/// nullopt when the plugin holds no information matrix or nothing can be
/// compared. A numerical failure of the test is a warning on stderr naming
/// the run, not a failed run: the test is a figure about the result.
std::optional<StateNees> finalStateNees(
	const FilterPlugin& plugin, const StateReference& reference,
	const std::optional<std::map<LandmarkId, LandmarkId>>& filter_to_reference, const std::string& what);

/// Sets state_nees, state_nees_dof, state_nees_lower95, state_nees_upper95,
/// state_nees_consistent (1/0), state_nees_poses and state_nees_reference
/// ("truth", a run folder, or null with every other key when not computed).
void setStateNeesStats(Stats& stats, const std::optional<StateNees>& nees, const std::string& reference);

/// Sets plugin_<name> for each of the plugin's own counters.
void setPluginCounters(Stats& stats, const CostFigures& cost);

/// Sets local_maps (maps fused), join_us_mean/p50/p99/max (each fusion's
/// time: `join_us` when the host timed it, else the plugin's own
/// LocalMapFusionCost::total_s) and join_association_us_mean (the plugin's
/// association time per fusion).
void setLocalMapJoinStats(
	Stats& stats, std::size_t local_maps, const std::vector<double>& join_us,
	const std::vector<LocalMapFusionCost>& costs);

}  // namespace esif
