#include "PluginPreload.h"

#include <esif/loader/PluginLoader.h>

#include <sstream>

namespace esif::app
{
void preloadPlugins(const std::optional<std::string>& plugin_dir)
{
	auto loader = PluginLoader::withExtraFolder(plugin_dir);
	std::ostringstream not_reported_here;  // each run that needs a broken file says so
	loader.loadAll(not_reported_here);
}

}  // namespace esif::app
