#include <esif/core/Errors.h>
#include <esif/eval/SuspectResult.h>
#include <esif/run/InitialRun.h>
#include <esif/run/RunSetup.h>
#include <esif/sim/MeasurementTruth.h>

#include <algorithm>
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
/// [esif] calibration = FILE: its path from the config's folder, its values
/// into host.noise. A noise set both there and by [esif] sensor_std_* is
/// an error: one run must not have two answers to one question.
void loadCalibration(HostParams& host, const ConfigSection& section, const std::string& config_path)
{
	const std::filesystem::path file(host.calibration);
	host.calibration = (file.is_absolute() ? file : std::filesystem::path(config_path).parent_path() / file)
						   .lexically_normal()
						   .string();
	if (!std::filesystem::is_regular_file(host.calibration))
		throw ConfigError(section.describeKey("calibration", host.calibration + ": no such file"));
	host.noise = loadNoiseCalibration(host.calibration);
	if (host.noise.range_std_m > 0 && host.sensor_std_range_m > 0)
		throw ConfigError(section.describeKey(
			"sensor_std_range_m", "set here and as range_std_m in " + host.calibration + ": keep one"));
	if (host.noise.bearing_std_deg > 0 && host.sensor_std_bearing_deg > 0)
		throw ConfigError(section.describeKey(
			"sensor_std_bearing_deg", "set here and as bearing_std_deg in " + host.calibration + ": keep one"));
}
}  // namespace

HostParams loadHostParams(const ConfigFile& cfg)
{
	HostParams host;
	const auto section = cfg.section(kHostSection);
	loadParams(host, section);
	if (host.plugin.empty())
		throw ConfigError(section.describeKey("plugin", "missing (no default): name the plugin class, see `esif plugins`"));
	if (host.label.empty()) host.label = std::filesystem::path(cfg.origin()).stem().string();
	section.rejectUnknownKeys();
	if (!host.calibration.empty()) loadCalibration(host, section, cfg.origin());
	return host;
}

FilterPlugin::Ptr createConfiguredPlugin(const ConfigFile& cfg, const HostParams& host, PluginLoader& loader)
{
	loader.loadAll();
	auto plugin = loader.create(host.plugin);
	const auto section = cfg.section(plugin->sectionName());
	plugin->configure(section);
	section.rejectUnknownKeys();
	requireInitialRunUse(cfg, host, *plugin);
	for (const auto& name : cfg.sectionNames())
		if (name != kHostSection && name != plugin->sectionName())
			throw ConfigError(
				cfg.origin() + ": [" + name + "]: unknown section (expected [" + kHostSection + "] and [" +
				plugin->sectionName() + "])");
	return plugin;
}

LocalMapJoiner* asLocalMapJoiner(FilterPlugin& plugin) { return dynamic_cast<LocalMapJoiner*>(&plugin); }

RawlogReadOptions readOptionsOf(const HostParams& host)
{
	RawlogReadOptions options;
	options.hide_landmark_ids = host.hide_landmark_ids;
	options.max_measurements_per_scan = static_cast<std::size_t>(host.max_measurements_per_scan);
	options.sensor_std_range_m = host.sensor_std_range_m;
	options.sensor_std_bearing_rad = host.sensor_std_bearing_deg * M_PI / 180.0;
	options.odometry_obs_std_xy_m = host.odometry_obs_std_xy_m;
	options.odometry_obs_std_phi_rad = host.odometry_obs_std_phi_deg * M_PI / 180.0;
	return options;
}

std::optional<std::string> locateAssociations(const ConfigFile& cfg, const HostParams& host, bool from_command_line)
{
	if (host.associations_from.empty()) return std::nullopt;
	const std::string path = (std::filesystem::path(host.associations_from) / kAssociationFileName).string();
	if (std::filesystem::is_regular_file(path)) return path;
	const std::string problem = path + " not found (run that config first)";
	if (from_command_line) throw ConfigError(cfg.origin() + ": --associations-from: " + problem);
	throw ConfigError(cfg.section(kHostSection).describeKey("associations_from", problem));
}

std::optional<GroundTruth> findGroundTruth(const std::optional<std::string>& prefix, const std::string& rawlog_path)
{
	if (prefix)
	{
		auto gt = loadGroundTruth(*prefix);
		if (!gt) throw InputError(*prefix + "_ground_truth.txt: ground truth not found");
		return gt;
	}
	return loadGroundTruth(groundTruthPrefixFor(rawlog_path));
}

std::vector<NamedInput> rawlogRunInputs(
	const std::string& config, const std::string& rawlog, const std::optional<std::string>& prefix,
	const std::optional<std::string>& associations_from)
{
	const std::string truth = prefix.value_or(groundTruthPrefixFor(rawlog));
	std::vector<NamedInput> inputs{{"the config", config}, {"the rawlog", rawlog}};
	for (const auto& file : groundTruthFilesOf(truth)) inputs.push_back({"the ground truth", file});
	inputs.push_back({"the ground truth", measurementTruthFileOf(truth)});
	// The folder named by --associations-from, else by the config (read
	// again here: it is checked before anything is written).
	const HostParams host = loadHostParams(ConfigFile::load(config));
	inputs.push_back({"the associations folder", associations_from.value_or(host.associations_from)});
	inputs.push_back({"the calibration file", host.calibration});
	inputs.push_back({"the initial run", host.initial_run});
	return inputs;
}

void flagSuspectResult(Stats& stats)
{
	if (const auto reason = markSuspect(stats))
		std::cerr << "esif: warning: suspect result: " << *reason
				  << " (stats.json suspect = 1; the outputs are written, look before using them)\n";
}

std::string effectiveParamsIni(const HostParams& host, const FilterPlugin& plugin)
{
	std::ostringstream out;
	out << "# Effective parameters of this run (defaults filled in).\n[" << kHostSection << "]\n";
	for (const auto& p : describeParams(host)) out << p.key << " = " << p.value << "\n";
	if (!host.calibration.empty())
	{
		out << "# the calibration file's values:\n";
		for (const auto& p : describeParams(host.noise)) out << "#   " << p.key << " = " << p.value << "\n";
	}
	out << "\n[" << plugin.sectionName() << "]\n";
	for (const auto& p : plugin.parameters()) out << p.key << " = " << p.value << "\n";
	return out.str();
}

double nearestRankPercentile(std::vector<double> values, double p)
{
	if (values.empty()) return 0;
	std::sort(values.begin(), values.end());
	const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(values.size())));
	return values[std::min(values.size() - 1, rank == 0 ? 0 : rank - 1)];
}

double peakRssMb()
{
	rusage usage{};
	getrusage(RUSAGE_SELF, &usage);
	return usage.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
}

void setTimeStats(Stats& s, const std::string& key, const std::vector<double>& us)
{
	s.set(key + "_mean", StatValue(us.empty() ? 0.0 : std::accumulate(us.begin(), us.end(), 0.0) / us.size()));
	s.set(key + "_p50", StatValue(nearestRankPercentile(us, 0.50)));
	s.set(key + "_p99", StatValue(nearestRankPercentile(us, 0.99)));
	s.set(key + "_max", StatValue(us.empty() ? 0.0 : *std::max_element(us.begin(), us.end())));
}

void setCostStats(Stats& s, const CostFigures& cost)
{
	s.set("state_dim", StatValue(static_cast<long long>(cost.state_dim)));
	s.set("poses_in_state", StatValue(static_cast<long long>(cost.poses_in_state)));
	if (cost.info_nnz)
		s.set("info_nnz", StatValue(static_cast<long long>(*cost.info_nnz)));
	else
		s.set("info_nnz", StatValue(nullptr));
}

void setAssociationStats(Stats& s, const AssociationAudit& audit)
{
	s.set("da_new", StatValue(static_cast<long long>(audit.newCount())));
	s.set("da_matched", StatValue(static_cast<long long>(audit.matchedCount())));
	s.set("da_rejected", StatValue(static_cast<long long>(audit.rejectedCount())));
	if (audit.hasTruth())
		s.set("da_wrong", StatValue(static_cast<long long>(audit.wrongCount())));
	else
		s.set("da_wrong", StatValue(nullptr));
	const auto tracked = [&](std::size_t n) {
		return audit.tracksGivenIds() ? StatValue(static_cast<long long>(n)) : StatValue(nullptr);
	};
	s.set("da_id_given", tracked(audit.givenIdCount()));
	s.set("da_id_rejected", tracked(audit.givenIdRejectedCount()));
}

void setAccuracyStats(Stats& s, const std::optional<Accuracy>& accuracy)
{
	const Accuracy acc = accuracy.value_or(Accuracy{});
	s.set("landmark_rmse_m", acc.landmark_rmse_m);
	s.set("ate_rmse_m", acc.ate_rmse_m);
	s.set("landmark_nees_mean", acc.landmark_nees_mean);
	s.set("pose_nees_mean", acc.pose_nees_mean);
	s.set("landmark_consistent_fraction", acc.landmark_consistent_fraction);
	s.set("pose_consistent_fraction", acc.pose_consistent_fraction);
	s.set("landmarks_evaluated", StatValue(static_cast<long long>(acc.landmarks_evaluated)));
}

std::optional<StateNees> finalStateNees(
	const FilterPlugin& plugin, const StateReference& reference,
	const std::optional<std::map<LandmarkId, LandmarkId>>& filter_to_reference, const std::string& what)
{
	const auto state = plugin.stateInformation();
	if (!state) return std::nullopt;
	try
	{
		return stateNees(*state, reference, filter_to_reference, what);
	}
	catch (const NumericalError& e)
	{
		std::cerr << "esif: warning: " << e.what() << "; state_nees left null\n";
		return std::nullopt;
	}
}

void setStateNeesStats(Stats& s, const std::optional<StateNees>& nees, const std::string& reference)
{
	if (!nees)
	{
		for (const char* key : {"state_nees", "state_nees_dof", "state_nees_lower95", "state_nees_upper95",
								"state_nees_consistent", "state_nees_poses", "state_nees_reference"})
			s.set(key, StatValue(nullptr));
		return;
	}
	s.set("state_nees", StatValue(nees->nees));
	s.set("state_nees_dof", StatValue(static_cast<long long>(nees->dof)));
	s.set("state_nees_lower95", StatValue(nees->lower95));
	s.set("state_nees_upper95", StatValue(nees->upper95));
	s.set("state_nees_consistent", StatValue(nees->consistent() ? 1LL : 0LL));
	s.set("state_nees_poses", StatValue(static_cast<long long>(nees->poses_compared)));
	s.set("state_nees_reference", StatValue(reference));
}

void setPluginCounters(Stats& s, const CostFigures& cost)
{
	for (const auto& [name, value] : cost.counters) s.set("plugin_" + name, StatValue(value));
}

void setLocalMapJoinStats(
	Stats& s, std::size_t local_maps, const std::vector<double>& join_us, const std::vector<LocalMapFusionCost>& costs)
{
	s.set("local_maps", StatValue(static_cast<long long>(local_maps)));
	std::vector<double> total_us = join_us, association_us;
	for (const auto& c : costs)
	{
		if (join_us.empty()) total_us.push_back(c.total_s * 1e6);
		association_us.push_back(c.association_s * 1e6);
	}
	setTimeStats(s, "join_us", total_us);
	if (association_us.empty())
		s.set("join_association_us_mean", StatValue(nullptr));
	else
		s.set(
			"join_association_us_mean",
			StatValue(std::accumulate(association_us.begin(), association_us.end(), 0.0) / association_us.size()));
}

}  // namespace esif
