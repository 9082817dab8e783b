#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/eval/Evaluator.h>
#include <esif/io/AssociationFile.h>
#include <esif/io/AtomicFile.h>
#include <esif/io/FigureWriter.h>
#include <esif/io/GroundTruth.h>
#include <esif/io/MapWriter.h>
#include <esif/io/RawlogReader.h>
#include <esif/run/HostParams.h>
#include <esif/run/LandmarkIdRequirement.h>
#include <esif/run/Replay.h>
#include <esif/run/RunPipeline.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numeric>
#include <sstream>
#include <sys/resource.h>

namespace esif
{
namespace
{
constexpr const char* kHostSection = "esif";
constexpr const char* kAssociationFile = "associations.txt";

HostParams loadHostParams(const ConfigFile& cfg)
{
	HostParams host;
	const auto section = cfg.section(kHostSection);
	loadParams(host, section);
	if (host.plugin.empty())
		throw ConfigError(section.describeKey("plugin", "missing (no default): name the plugin class, see `esif plugins`"));
	if (host.label.empty()) host.label = std::filesystem::path(cfg.origin()).stem().string();
	section.rejectUnknownKeys();
	return host;
}

FilterPlugin::Ptr createConfiguredPlugin(const ConfigFile& cfg, const HostParams& host, PluginLoader& loader)
{
	loader.loadAll();
	auto plugin = loader.create(host.plugin);
	const auto section = cfg.section(plugin->sectionName());
	plugin->configure(section);
	section.rejectUnknownKeys();
	for (const auto& name : cfg.sectionNames())
		if (name != kHostSection && name != plugin->sectionName())
			throw ConfigError(
				cfg.origin() + ": [" + name + "]: unknown section (expected [" + kHostSection + "] and [" +
				plugin->sectionName() + "])");
	return plugin;
}

/// DIR/associations.txt of `host.associations_from` (already overridden by the
/// request), checked before the rawlog is read so that a wrong folder fails
/// at once; nullopt when the rawlog's own IDs are used.
std::optional<std::string> locateAssociations(const ConfigFile& cfg, const HostParams& host, const RunRequest& request)
{
	if (host.associations_from.empty()) return std::nullopt;
	const std::string path = (std::filesystem::path(host.associations_from) / kAssociationFile).string();
	if (std::filesystem::is_regular_file(path)) return path;
	const std::string problem = path + " not found (run that config first)";
	if (request.associations_from) throw ConfigError(cfg.origin() + ": --associations-from: " + problem);
	throw ConfigError(cfg.section(kHostSection).describeKey("associations_from", problem));
}

RawlogReadOptions readOptionsOf(const HostParams& host)
{
	RawlogReadOptions options;
	options.hide_landmark_ids = host.hide_landmark_ids;
	options.sensor_std_range_m = host.sensor_std_range_m;
	options.sensor_std_bearing_rad = host.sensor_std_bearing_deg * M_PI / 180.0;
	options.odometry_obs_std_xy_m = host.odometry_obs_std_xy_m;
	options.odometry_obs_std_phi_rad = host.odometry_obs_std_phi_deg * M_PI / 180.0;
	return options;
}

std::optional<GroundTruth> findGroundTruth(const RunRequest& request)
{
	if (request.ground_truth_prefix)
	{
		auto gt = loadGroundTruth(*request.ground_truth_prefix);
		if (!gt) throw InputError(*request.ground_truth_prefix + "_ground_truth.txt: ground truth not found");
		return gt;
	}
	return loadGroundTruth(groundTruthPrefixFor(request.rawlog_path));
}

double percentile(std::vector<double> v, double p)
{
	if (v.empty()) return 0;
	std::sort(v.begin(), v.end());
	// Nearest-rank percentile: the smallest value with at least p of the data at or below it.
	const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(v.size())));
	return v[std::min(v.size() - 1, rank == 0 ? 0 : rank - 1)];
}

double peakRssMb()
{
	rusage usage{};
	getrusage(RUSAGE_SELF, &usage);
	return usage.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
}

Stats collectStats(
	const HostParams& host, const RunRequest& request, const Rawlog& log, const ReplayResult& result,
	const FilterPlugin& plugin, const std::optional<Accuracy>& accuracy, double total_wall_s)
{
	Stats s;
	const auto& us = result.step_us;
	const auto cost = plugin.costFigures();
	s.set("plugin", StatValue(host.plugin));
	s.set("formulation", StatValue(std::string(formulationName(plugin.formulation()))));
	s.set("label", StatValue(host.label));
	s.set("config", StatValue(request.config_path));
	s.set("rawlog", StatValue(request.rawlog_path));
	s.set("steps", StatValue(static_cast<long long>(log.steps.size())));
	s.set("measurements", StatValue(static_cast<long long>(log.measurement_count)));
	s.set("landmarks", StatValue(static_cast<long long>(result.record.final_estimate.landmarks.size())));
	s.set("wall_s", StatValue(result.wall_s));
	s.set("total_wall_s", StatValue(total_wall_s));
	s.set("step_us_mean", StatValue(us.empty() ? 0.0 : std::accumulate(us.begin(), us.end(), 0.0) / us.size()));
	s.set("step_us_p50", StatValue(percentile(us, 0.50)));
	s.set("step_us_p99", StatValue(percentile(us, 0.99)));
	s.set("step_us_max", StatValue(us.empty() ? 0.0 : *std::max_element(us.begin(), us.end())));
	s.set("finish_us", StatValue(result.finish_us));
	s.set("peak_rss_mb", StatValue(peakRssMb()));
	s.set("state_dim", StatValue(static_cast<long long>(cost.state_dim)));
	s.set("poses_in_state", StatValue(static_cast<long long>(cost.poses_in_state)));
	if (cost.info_nnz)
		s.set("info_nnz", StatValue(static_cast<long long>(*cost.info_nnz)));
	else
		s.set("info_nnz", StatValue(nullptr));
	s.set("da_new", StatValue(static_cast<long long>(result.audit.newCount())));
	s.set("da_matched", StatValue(static_cast<long long>(result.audit.matchedCount())));
	s.set("da_rejected", StatValue(static_cast<long long>(result.audit.rejectedCount())));
	if (result.audit.hasTruth())
		s.set("da_wrong", StatValue(static_cast<long long>(result.audit.wrongCount())));
	else
		s.set("da_wrong", StatValue(nullptr));
	const Accuracy acc = accuracy.value_or(Accuracy{});
	s.set("landmark_rmse_m", acc.landmark_rmse_m);
	s.set("ate_rmse_m", acc.ate_rmse_m);
	s.set("landmark_nees_mean", acc.landmark_nees_mean);
	s.set("pose_nees_mean", acc.pose_nees_mean);
	s.set("landmark_consistent_fraction", acc.landmark_consistent_fraction);
	s.set("pose_consistent_fraction", acc.pose_consistent_fraction);
	s.set("landmarks_evaluated", StatValue(static_cast<long long>(acc.landmarks_evaluated)));
	s.set("truncated", StatValue(log.truncation_warning ? 1LL : 0LL));
	for (const auto& [name, value] : cost.counters) s.set("plugin_" + name, StatValue(value));
	return s;
}

std::string effectiveParamsIni(const HostParams& host, const FilterPlugin& plugin)
{
	std::ostringstream out;
	out << "# Effective parameters of this run (defaults filled in).\n[" << kHostSection << "]\n";
	for (const auto& p : describeParams(host)) out << p.key << " = " << p.value << "\n";
	out << "\n[" << plugin.sectionName() << "]\n";
	for (const auto& p : plugin.parameters()) out << p.key << " = " << p.value << "\n";
	return out.str();
}
}  // namespace

Stats runPipeline(const RunRequest& request, PluginLoader& loader)
{
	const auto t0 = std::chrono::steady_clock::now();
	const ConfigFile cfg = ConfigFile::load(request.config_path);
	HostParams host = loadHostParams(cfg);
	if (request.associations_from) host.associations_from = *request.associations_from;	// params.ini shows the folder used
	auto plugin = createConfiguredPlugin(cfg, host, loader);
	const auto associations = locateAssociations(cfg, host, request);

	Rawlog log = readRawlog(request.rawlog_path, readOptionsOf(host));
	if (log.truncation_warning) std::cerr << "esif: warning: " << *log.truncation_warning << "\n";
	if (associations) applyAssociations(log, readAssociationFile(*associations), *associations);
	requireLandmarkIds(*plugin, log, {cfg.origin(), host.hide_landmark_ids, associations.value_or("")});
	const auto truth = findGroundTruth(request);
	ensureDirectory(request.out_dir);

	ReplayResult result = replay(*plugin, log, {host.keyframe_min_distance_m, request.progress_bar});

	std::optional<Accuracy> accuracy;
	if (truth)
	{
		result.record.truth = truth->inInitialPoseFrame();
		std::map<LandmarkId, LandmarkId> filter_to_true = result.audit.filterToTrue();
		accuracy = evaluate(*result.record.truth, result.record.trajectory, result.record.final_estimate, filter_to_true);
	}

	MapWriterOptions map_options;
	map_options.image_size_px = host.image_size_px;
	writeMapOutputs(result.record, request.out_dir, map_options);
	const auto dir = std::filesystem::path(request.out_dir);
	writeStepTimesImage(result.step_us, result.landmark_counts, (dir / "step_times.png").string(), host.image_size_px);
	if (const auto pattern = plugin->informationPattern())
		writeInformationPatternImage(*pattern, (dir / "info_matrix.png").string(), host.image_size_px);
	writeTextAtomically((dir / "params.ini").string(), effectiveParamsIni(host, *plugin));
	writeAssociationFile((dir / kAssociationFile).string(), result.reports, host.plugin, request.rawlog_path);
	const double total_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	Stats stats = collectStats(host, request, log, result, *plugin, accuracy, total_wall_s);
	writeTextAtomically((dir / "stats.json").string(), stats.toJson());
	return stats;
}

}  // namespace esif
