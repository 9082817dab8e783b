#pragma once
/// \file PluginLoader.h
/// Finds plugin libraries (libesif_plugin_*.so) in the plugin folders, loads
/// them with mrpt::system::loadPluginModule and creates filters by class name.

#include <esif/plugin/FilterPlugin.h>

#include <string>
#include <vector>

namespace esif
{
class PluginLoader
{
   public:
	/// Plugin folders: `dirs` first, then $ESIF_PLUGIN_PATH (colon separated),
	/// then the folder beside the host binary (../lib/esif).
	explicit PluginLoader(std::vector<std::string> dirs = {});

	/// Loads every libesif_plugin_*.so once; throws InputError if one fails to load.
	void loadAll();

	/// Class names of all registered FilterPlugin classes (without "esif::").
	std::vector<std::string> available() const;

	/// Creates the plugin `class_name` ("EkfSlam" or "esif::EkfSlam"); throws
	/// ConfigError listing the available plugins when it is unknown.
	FilterPlugin::Ptr create(const std::string& class_name) const;

	/// Library files loaded so far.
	const std::vector<std::string>& loadedFiles() const { return loaded_; }

	/// The folders searched, in order.
	const std::vector<std::string>& searchDirs() const { return dirs_; }

   private:
	std::vector<std::string> dirs_;
	std::vector<std::string> loaded_;
};

}  // namespace esif
