#include <esif/core/Errors.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/run/InitialRun.h>
#include <esif/run/RunConfig.h>

#include <filesystem>

namespace esif
{
namespace
{
constexpr const char* kKey = "initial_run";

std::string describeKey(const ConfigFile& cfg, const std::string& problem)
{
	return cfg.section(kHostSection).describeKey(kKey, problem);
}
}  // namespace

void requireInitialRunUse(const ConfigFile& cfg, const HostParams& host, const FilterPlugin& plugin)
{
	if (host.initial_run.empty() || plugin.usesInitialEstimate()) return;
	throw ConfigError(describeKey(cfg, "plugin " + host.plugin + " does not start from another run's estimate"));
}

std::optional<InitialEstimate> readInitialRun(const ConfigFile& cfg, const HostParams& host)
{
	if (host.initial_run.empty()) return std::nullopt;
	const std::string& dir = host.initial_run;
	if (!std::filesystem::is_directory(dir)) throw InputError(describeKey(cfg, dir + ": run folder not found"));
	InitialEstimate estimate;
	estimate.source = (std::filesystem::path(dir) / "trajectory.tum").string();
	try
	{
		const RunOutputs run = readRunOutputs(dir);
		for (const auto& p : run.trajectory) estimate.poses.push_back(toPose2(p.pose));
		for (const auto& l : run.landmarks)
			if (l.mean.allFinite()) estimate.landmarks.emplace(l.id, l.mean);
	}
	catch (const InputError& e)
	{
		throw InputError(describeKey(cfg, e.what()));
	}
	return estimate;
}

void requireInitialRunCovers(const ConfigFile& cfg, const InitialEstimate& estimate, std::size_t steps)
{
	if (estimate.poses.size() >= steps) return;
	throw InputError(describeKey(
		cfg, estimate.source + ": " + std::to_string(estimate.poses.size()) + " poses, the rawlog has " +
				 std::to_string(steps) + " steps (is it the run of another rawlog?)"));
}

}  // namespace esif
