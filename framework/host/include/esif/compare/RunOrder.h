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
};

/// For each run, the index of the compared run whose label its
/// associations_from names; nullopt when empty or no other run has that label
/// (it is then a folder). Throws ConfigError for a config naming its own
/// label only, or a label several other configs share.
std::vector<std::optional<std::size_t>> associationSources(const std::vector<PlannedRun>& runs);

/// Indices of `runs` in run order: `first` (the reference the others are
/// measured against) as early as its sources allow, each source (from
/// associationSources) just before the first run that needs it, otherwise
/// the given order. Throws ConfigError naming the configs of a cycle
/// (a -> b -> a).
std::vector<std::size_t> runOrder(
	const std::vector<PlannedRun>& runs, const std::vector<std::optional<std::size_t>>& sources,
	std::optional<std::size_t> first = std::nullopt);

}  // namespace esif
