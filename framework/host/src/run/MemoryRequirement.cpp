#include <esif/core/Errors.h>
#include <esif/core/NumberToken.h>
#include <esif/loader/PluginName.h>
#include <esif/run/MemoryRequirement.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <set>
#include <sys/resource.h>
#include <unistd.h>

namespace esif
{
namespace
{
std::string gibibytes(double bytes)
{
	char text[64];
	std::snprintf(text, sizeof(text), "%.3g GiB", bytes / (1024.0 * 1024.0 * 1024.0));
	return text;
}

void lowerTo(MemoryBudget& budget, double bytes, const char* set_by)
{
	if (bytes > 0 && bytes < budget.bytes) budget = {bytes, set_by};
}

/// The cgroup v2 limit of this process's group, if there is one: a number
/// of bytes, or "max" for none.
std::optional<double> cgroupLimit()
{
	std::ifstream in("/sys/fs/cgroup/memory.max");
	std::string word;
	if (!(in >> word)) return std::nullopt;
	const auto bytes = integerToken<std::uint64_t>(word);
	return bytes ? std::optional<double>(static_cast<double>(*bytes)) : std::nullopt;
}
}  // namespace

std::optional<std::size_t> landmarksInLog(const Rawlog& log, const RecordedAssociations* recorded)
{
	std::set<LandmarkId> ids;
	for (const auto& step : log.true_ids)
		for (const auto& id : step)
			if (id) ids.insert(*id);
	if (ids.empty() && recorded)
		for (const auto& step : recorded->steps)
			for (const auto& a : step.associations)
				if (a.kind != Association::Kind::Rejected) ids.insert(a.id);
	if (ids.empty())
		for (const auto& step : log.steps)
			if (step.scan)
				for (const auto& m : step.scan->measurements)
					if (m.id) ids.insert(*m.id);
	return ids.empty() ? std::nullopt : std::optional<std::size_t>(ids.size());
}

MemoryBudget memoryBudget()
{
	MemoryBudget budget{static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE)),
						"physical memory"};
	for (const auto& [resource, name] : {std::pair{RLIMIT_AS, "RLIMIT_AS"}, std::pair{RLIMIT_DATA, "RLIMIT_DATA"}})
	{
		rlimit limit{};
		if (::getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
			lowerTo(budget, static_cast<double>(limit.rlim_cur), name);
	}
	if (const auto cgroup = cgroupLimit()) lowerTo(budget, *cgroup, "cgroup memory.max");
	return budget;
}

void requireMemory(const FilterPlugin& plugin, const Rawlog& log, const std::string& config_path,
				   const MemoryBudget& budget, const RecordedAssociations* recorded)
{
	const auto landmarks = landmarksInLog(log, recorded);
	if (!landmarks) return;
	const auto bytes = plugin.bytesForLandmarks(*landmarks);
	if (!bytes || *bytes <= budget.bytes) return;
	throw ConfigError(config_path + ": plugin " + iniClassName(plugin) + " would need " + gibibytes(*bytes) +
					  " for its estimate of the " + std::to_string(*landmarks) + " landmarks of " + log.path +
					  ", more than the " + gibibytes(budget.bytes) + " this process may use (" + budget.set_by +
					  "): choose a sparse information filter for a map this size");
}

}  // namespace esif
