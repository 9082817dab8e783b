#include "CommandLine.h"
#include "Commands.h"

#include <esif/plugin/PluginLoader.h>

#include <iostream>

namespace esif::app
{
int pluginsCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd("Lists the plugins found and their INI parameters with defaults.", ' ', ESIF_VERSION);
	TCLAP::ValueArg<std::string> plugin_dir("", "plugin-dir", "extra folder to search for plugins", false, "", "DIR",
											cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;

	PluginLoader loader(plugin_dir.isSet() ? std::vector<std::string>{plugin_dir.getValue()} : std::vector<std::string>{});
	loader.loadAll();
	std::cout << "Plugin folders searched:";
	for (const auto& d : loader.searchDirs()) std::cout << " " << d;
	std::cout << "\n";
	const auto names = loader.available();
	if (names.empty()) std::cout << "No plugins found.\n";
	for (const auto& name : names)
	{
		const auto plugin = loader.create(name);
		std::cout << "\n" << name << "    ([esif] plugin = " << name << ", parameters in [" << plugin->sectionName()
				  << "])\n";
		for (const auto& p : plugin->parameters())
			std::cout << "  " << p.key << " = " << p.value << "\n      " << p.doc << "\n";
	}
	return 0;
}

}  // namespace esif::app
