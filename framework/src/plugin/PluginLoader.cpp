#include <esif/core/Errors.h>
#include <esif/plugin/PluginLoader.h>

#include <mrpt/rtti/CObject.h>
#include <mrpt/system/os.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace esif
{
namespace
{
constexpr const char* kPrefix = "libesif_plugin_";
constexpr const char* kNamespace = "esif::";

/// ../lib/esif relative to the running executable, where the build and
/// install put the plugins.
std::string folderBesideExecutable()
{
	std::error_code ec;
	const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
	if (ec) return {};
	return (exe.parent_path().parent_path() / "lib" / "esif").string();
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

void PluginLoader::loadAll()
{
	std::set<std::string> seen_names;
	for (const auto& dir : dirs_)
	{
		std::error_code ec;
		if (!fs::is_directory(dir, ec)) continue;
		std::vector<fs::path> files;
		for (const auto& entry : fs::directory_iterator(dir, ec))
		{
			const auto name = entry.path().filename().string();
			if (name.rfind(kPrefix, 0) == 0 && entry.path().extension() == ".so") files.push_back(entry.path());
		}
		std::sort(files.begin(), files.end());
		for (const auto& file : files)
		{
			// A plugin of the same file name found earlier in the search path wins.
			if (!seen_names.insert(file.filename().string()).second) continue;
			const auto path = fs::absolute(file).string();
			if (std::find(loaded_.begin(), loaded_.end(), path) != loaded_.end()) continue;
			std::string err;
			if (!mrpt::system::loadPluginModule(path, err))
				throw InputError(path + ": cannot load plugin: " + err);
			loaded_.push_back(path);
		}
	}
	mrpt::rtti::registerAllPendingClasses();
}

std::vector<std::string> PluginLoader::available() const
{
	std::vector<std::string> out;
	for (const auto* cls : mrpt::rtti::getAllRegisteredClassesChildrenOf(CLASS_ID_NAMESPACE(FilterPlugin, esif)))
	{
		if (!cls->ptrCreateObject) continue;  // abstract
		std::string name = cls->className;
		if (name.rfind(kNamespace, 0) == 0) name.erase(0, std::string(kNamespace).size());
		out.push_back(name);
	}
	std::sort(out.begin(), out.end());
	return out;
}

FilterPlugin::Ptr PluginLoader::create(const std::string& class_name) const
{
	const std::string full = class_name.rfind(kNamespace, 0) == 0 ? class_name : kNamespace + class_name;
	const auto* cls = mrpt::rtti::findRegisteredClass(full);
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
		throw ConfigError(
			"unknown plugin '" + class_name + "' (available: " + list + "; searched " + dirs + ")");
	}
	return plugin;
}

}  // namespace esif
