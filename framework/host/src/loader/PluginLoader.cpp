#include <esif/core/Errors.h>
#include <esif/loader/PluginLoader.h>
#include <esif/loader/PluginName.h>

#include "SealedLibrary.h"

#include <mrpt/rtti/CObject.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <set>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace esif
{
namespace
{
constexpr const char* kPrefix = "libesif_plugin_";

/// ../lib/esif relative to the running executable, where the build and
/// install put the plugins.
std::string folderBesideExecutable()
{
	std::error_code ec;
	const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
	if (ec) return {};
	return (exe.parent_path().parent_path() / "lib" / "esif").string();
}

/// The plugin files of `dir` (libesif_plugin_*.so), sorted; none when it is
/// not a folder.
std::vector<fs::path> pluginFilesIn(const std::string& dir)
{
	std::vector<fs::path> files;
	std::error_code ec;
	if (!fs::is_directory(dir, ec)) return files;
	for (const auto& entry : fs::directory_iterator(dir, ec))
	{
		const auto name = entry.path().filename().string();
		if (name.rfind(kPrefix, 0) == 0 && entry.path().extension() == ".so") files.push_back(entry.path());
	}
	std::sort(files.begin(), files.end());
	return files;
}

/// `reason` on one line.
std::string oneLine(std::string reason)
{
	std::replace(reason.begin(), reason.end(), '\n', ' ');
	while (!reason.empty() && reason.back() == ' ') reason.pop_back();
	return reason;
}

std::vector<std::string> splitColons(const char* text)
{
	std::vector<std::string> out;
	if (!text) return out;
	std::stringstream ss(text);
	std::string item;
	while (std::getline(ss, item, ':'))
		if (!item.empty()) out.push_back(item);
	return out;
}
}  // namespace

PluginLoader::PluginLoader(std::vector<std::string> dirs) : dirs_(std::move(dirs))
{
	for (auto& d : splitColons(std::getenv("ESIF_PLUGIN_PATH"))) dirs_.push_back(d);
	const auto beside = folderBesideExecutable();
	if (!beside.empty()) dirs_.push_back(beside);
}

PluginLoader PluginLoader::withExtraFolder(const std::optional<std::string>& extra_dir)
{
	return PluginLoader(extra_dir ? std::vector<std::string>{*extra_dir} : std::vector<std::string>{});
}

void PluginLoader::loadAll(std::ostream& warnings)
{
	std::set<std::string> loaded_names;
	for (const auto& path : loaded_) loaded_names.insert(fs::path(path).filename().string());
	for (const auto& dir : dirs_)
		for (const auto& file : pluginFilesIn(dir))
		{
			// A plugin of the same file name loaded from earlier in the search
			// path wins; a broken one does not hide a good one further on.
			if (loaded_names.count(file.filename().string())) continue;
			const auto path = fs::absolute(file).string();
			if (isBroken(path)) continue;  // reported once, not on every call
			// Copied, sealed and checked before it is mapped (SealedLibrary.h):
			// a FIFO or a file cut short is a warning, not a hang or SIGBUS.
			const LibraryLoad load = loadSealedLibrary(path);
			if (load.handle)
			{
				loaded_.push_back(path);
				loaded_names.insert(file.filename().string());
				continue;
			}
			broken_.push_back({path, oneLine(load.problem)});
			warnings << "esif: warning: " << path << ": cannot load plugin, skipped (" << broken_.back().reason
					 << ")\n";
		}
	mrpt::rtti::registerAllPendingClasses();
}

bool PluginLoader::isBroken(const std::string& path) const
{
	return std::any_of(broken_.begin(), broken_.end(), [&](const BrokenPlugin& b) { return b.path == path; });
}

std::vector<std::string> PluginLoader::available() const
{
	std::vector<std::string> out;
	for (const auto* cls : mrpt::rtti::getAllRegisteredClassesChildrenOf(CLASS_ID_NAMESPACE(FilterPlugin, esif)))
	{
		if (!cls->ptrCreateObject) continue;  // abstract
		out.push_back(iniClassName(cls->className));
	}
	std::sort(out.begin(), out.end());
	return out;
}

FilterPlugin::Ptr PluginLoader::create(const std::string& class_name) const
{
	const auto* cls = mrpt::rtti::findRegisteredClass(registeredClassName(class_name));
	FilterPlugin::Ptr plugin;
	if (cls && cls->derivedFrom(CLASS_ID_NAMESPACE(FilterPlugin, esif)) && cls->ptrCreateObject)
		plugin = std::dynamic_pointer_cast<FilterPlugin>(cls->createObject());
	if (!plugin)
	{
		std::string list;
		for (const auto& n : available()) list += (list.empty() ? "" : ", ") + n;
		if (list.empty()) list = "none found";
		std::string dirs;
		for (const auto& d : dirs_) dirs += (dirs.empty() ? "" : ":") + d;
		// Any file that failed to load may have been the plugin asked for.
		std::string broken;
		for (const auto& b : broken_) broken += (broken.empty() ? "" : ", ") + b.path + " (" + b.reason + ")";
		throw ConfigError(
			"unknown plugin '" + class_name + "' (available: " + list + "; searched " + dirs + ")" +
			(broken.empty() ? "" : "; files that failed to load, one may be it: " + broken));
	}
	return plugin;
}

}  // namespace esif
