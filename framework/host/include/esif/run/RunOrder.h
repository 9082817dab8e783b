#pragma once
/// \file RunOrder.h
/// The order in which `esif compare` runs its configs when one reuses
/// another's data association (`[esif] associations_from = LABEL` naming
/// another compared config): the config named runs first, the rest keep the
/// given order. Found before any run, so a bad reference costs nothing.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// One compared config, as far as its place in the run order matters.
struct PlannedRun
{
	std::string config;	 ///< INI path, for messages
	std::string label;	///< the label its run will carry
	std::string associations_from;	///< its [esif] associations_from (empty: none)
	bool hide_landmark_ids = false;	 ///< its [esif] hide_landmark_ids
};

/// For each run, the index of the compared run whose label its
/// associations_from names; nullopt when empty or no other run has that label
/// (it is then a folder). Throws ConfigError for a config naming its own
/// label only, or a label several other configs share.
std::vector<std::optional<std::size_t>> associationSources(const std::vector<PlannedRun>& runs);

/// Where the landmark IDs of run `i`'s outputs come from, for warnings when
/// runs are compared by landmark ID: "from the rawlog", "numbered by run
/// 'LABEL' itself" (IDs hidden, no associations_from), "from DIR/associations.txt"
/// or, through `sources`, the origin of the run it takes its association from.
/// A plugin that ignores IDs it is shown is not detected (a config cannot tell).
std::string landmarkIdOrigin(
	const std::vector<PlannedRun>& runs, const std::vector<std::optional<std::size_t>>& sources, std::size_t i);

/// Indices of `runs` in run order: each source (from associationSources)
/// just before the first run that needs it, otherwise the given order.
/// Throws ConfigError naming the configs of a cycle (a -> b -> a).
std::vector<std::size_t> runOrder(
	const std::vector<PlannedRun>& runs, const std::vector<std::optional<std::size_t>>& sources);

}  // namespace esif
