#include "PluginPreload.h"

#include <esif/run/PluginLoader.h>

#include <sstream>
#include <vector>

namespace esif::app
{
void preloadPlugins(const std::optional<std::string>& plugin_dir)
{
	PluginLoader loader(plugin_dir ? std::vector<std::string>{*plugin_dir} : std::vector<std::string>{});
	std::ostringstream not_reported_here;  // each run that needs a broken file says so
	loader.loadAll(not_reported_here);
}

}  // namespace esif::app
