#pragma once
/// \file MemoryRequirement.h
/// The host's check, before the replay, that a plugin whose memory grows
/// with a dense matrix (FilterPlugin::bytesForLandmarks: the EKF's
/// covariance) fits this machine for the map the rawlog holds: a city-sized
/// log is refused with one line naming the memory it would need, rather
/// than swapping for hours or being killed by the kernel.

#include <esif/formats/AssociationFile.h>
#include <esif/formats/RawlogReader.h>
#include <esif/plugin/FilterPlugin.h>

#include <cstddef>
#include <optional>
#include <string>

namespace esif
{
/// How many landmarks `log` holds, when it says: the distinct true landmarks
/// of its measurements (the rawlog's IDs, kept even when hidden from the
/// plugin, or the simulator's measurement truth); nullopt when no
/// measurement carries an ID. Without true landmarks, those of a recorded
/// run's associations when the plugin is given them (`recorded`), else of
/// the steps kept.
std::optional<std::size_t> landmarksInLog(const Rawlog& log, const RecordedAssociations* recorded = nullptr);

/// The memory a process may use here [bytes] and what sets it: the smallest
/// of the physical memory, the soft RLIMIT_AS and RLIMIT_DATA, and the
/// cgroup v2 limit (memory.max, as Slurm and containers set it).
struct MemoryBudget
{
	double bytes = 0;
	std::string set_by;	 ///< e.g. "physical memory", "RLIMIT_AS", "cgroup memory.max"
};
MemoryBudget memoryBudget();

/// Throws ConfigError naming `config_path`, the plugin, the landmarks and
/// both amounts when `plugin` says its estimate of the log's landmarks needs
/// more than `budget`.
void requireMemory(const FilterPlugin& plugin, const Rawlog& log, const std::string& config_path,
				   const MemoryBudget& budget, const RecordedAssociations* recorded = nullptr);

}  // namespace esif
