#include <esif/core/Errors.h>
#include <esif/formats/MeasurementTruth.h>
#include <esif/run/InitialRun.h>
#include <esif/run/RunConfig.h>

#include <cmath>
#include <filesystem>
#include <sstream>

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

LocalMapJoiner& requireLocalMapJoiner(FilterPlugin& plugin, const std::string& config, const std::string& name)
{
	if (auto* joiner = asLocalMapJoiner(plugin)) return *joiner;
	throw ConfigError(
		config + ": plugin " + name + " cannot join local maps (--local-maps needs a local-map joining plugin)");
}

RawlogReadOptions readOptionsOf(const HostParams& host)
{
	RawlogReadOptions options;
	options.hide_landmark_ids = host.hide_landmark_ids;
	options.max_measurements_per_scan = static_cast<std::size_t>(host.max_measurements_per_scan);
	options.sensor_std_range_m = host.sensor_std_range_m;
	options.sensor_std_bearing_rad = host.sensor_std_bearing_deg * M_PI / 180.0;
	options.odometry_obs_std_xy_m = host.odometry_obs_std_xy_m;
	options.odometry_obs_std_phi_rad = host.odometry_obs_std_phi_deg * M_PI / 180.0;
	// map.simplemap reads its keyframes' frames again from the file
	// (RawlogFrames.h): a large log's frames are most of its memory.
	options.keep_frames = false;
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

}  // namespace esif
