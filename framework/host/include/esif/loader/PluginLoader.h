#pragma once
/// \file PluginLoader.h
/// Finds plugin libraries (libesif_plugin_*.so) in the plugin folders, loads
/// them from sealed, checked copies (loader/SealedLibrary.h: no file at a
/// plugin's name can hang or crash esif) and creates filters by class name.

#include <esif/plugin/FilterPlugin.h>

#include <iostream>
#include <optional>
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
	/// The default folders, after `extra_dir` (a command's --plugin-dir) if given.
	static PluginLoader withExtraFolder(const std::optional<std::string>& extra_dir);

	/// Loads every libesif_plugin_*.so once. A file that fails to load (not a
	/// regular file, cut short, not a library, missing symbols, another
	/// architecture) is skipped with a warning line on `warnings` naming it
	/// and the reason, and kept in brokenFiles(); the others are still
	/// loaded. Only asking for a plugin that is then not found is an error
	/// (create()).
	void loadAll(std::ostream& warnings = std::cerr);

	/// Class names of all registered FilterPlugin classes (without "esif::").
	std::vector<std::string> available() const;

	/// Creates the plugin `class_name` ("EkfSlam" or "esif::EkfSlam"); throws
	/// ConfigError listing the available plugins, and the files that failed
	/// to load (any may have been it), when it is unknown.
	FilterPlugin::Ptr create(const std::string& class_name) const;

	/// A plugin file that failed to load, and why (esif's check or dlerror's text).
	struct BrokenPlugin
	{
		std::string path;
		std::string reason;
	};

	/// Files that failed to load so far.
	const std::vector<BrokenPlugin>& brokenFiles() const { return broken_; }

	/// The folders searched, in order.
	const std::vector<std::string>& searchDirs() const { return dirs_; }

   private:
	bool isBroken(const std::string& path) const;

	std::vector<std::string> dirs_;
	std::vector<std::string> loaded_;
	std::vector<BrokenPlugin> broken_;
};

}  // namespace esif
