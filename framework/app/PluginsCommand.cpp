#include "CommandLine.h"
#include "Commands.h"

#include <esif/run/HostParams.h>
#include <esif/run/PluginLoader.h>

#include <iostream>

namespace esif::app
{
int pluginsCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd(
		"Lists the host's [esif] keys, the plugins found and their INI parameters, each with its default.", ' ',
		ESIF_VERSION);
	TCLAP::ValueArg<std::string> plugin_dir("", "plugin-dir", "extra folder to search for plugins", false, "", "DIR",
											cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;

	PluginLoader loader(plugin_dir.isSet() ? std::vector<std::string>{plugin_dir.getValue()} : std::vector<std::string>{});
	loader.loadAll();
	std::cout << "Plugin folders searched:";
	for (const auto& d : loader.searchDirs()) std::cout << " " << d;
	std::cout << "\n";
	// The host's own section first: every config has one.
	std::cout << "\n[esif]    (the host: which plugin runs, how the rawlog becomes its input, outputs)\n";
	for (const auto& p : describeParams(HostParams{}))
		std::cout << "  " << p.key << " = " << p.value << "\n      " << p.doc << "\n";
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
