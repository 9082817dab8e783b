#pragma once
/// \file ConfigCheck.h
/// The configs of a command that runs several (`esif compare`, `esif
/// montecarlo`), checked in this process before the first run, as `esif run`
/// would check each: the file, [esif], the plugin found and configured from
/// its section, and on local-map input a joining plugin. A mistake in the
/// last config is then one error line naming it before any run has cost
/// time and before any output folder exists.

#include <esif/core/Estimate.h>

#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// What checking a config found out before any run.
struct CheckedConfig
{
	std::string plugin;	 ///< [esif] plugin
	Formulation formulation = Formulation::Other;
};

/// One entry per config, in order; throws ConfigError naming the config.
/// `plugin_dir`: an extra plugin folder; `local_maps`: the input is a folder
/// of local maps, so every plugin must join them.
std::vector<CheckedConfig> checkConfigs(const std::vector<std::string>& configs,
										const std::optional<std::string>& plugin_dir = std::nullopt,
										bool local_maps = false);

}  // namespace esif
