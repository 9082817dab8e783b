#pragma once
/// \file PluginPreload.h
/// Commands whose runs are forks of the run server (RunServer.h: `esif
/// compare`, `esif montecarlo`) load the plugins into themselves before the
/// server starts. Every run is then born with the plugin libraries mapped
/// and their classes registered, so its own PluginLoader finds them loaded
/// instead of loading (and relocating) every plugin file again, Ceres's
/// included, once per run.

#include <optional>
#include <string>

namespace esif::app
{
/// Loads the plugins of the default folders and of `plugin_dir`. Call it
/// where a RunServer may still be started (single-threaded). A file that
/// fails to load is left to the runs, which report it as `esif run` does.
void preloadPlugins(const std::optional<std::string>& plugin_dir = std::nullopt);

}  // namespace esif::app
