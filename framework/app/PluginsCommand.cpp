#include "CommandLine.h"
#include "Commands.h"

#include <esif/run/HostParams.h>
#include <esif/loader/PluginLoader.h>

#include <iostream>
#include <sstream>

namespace esif::app
{
std::string pluginListing(const std::vector<std::string>& extra_dirs)
{
	PluginLoader loader(extra_dirs);
	loader.loadAll();
	std::ostringstream out;
	out << "Plugin folders searched:";
	for (const auto& d : loader.searchDirs()) out << " " << d;
	out << "\n";
	// The host's own section first: every config has one.
	out << "\n[esif]    (the host: which plugin runs, how the rawlog becomes its input, outputs)\n";
	for (const auto& p : describeParams(HostParams{}))
		out << "  " << p.key << " = " << p.value << "\n      " << p.doc << "\n";
	const auto names = loader.available();
	if (names.empty()) out << "No plugins found.\n";
	for (const auto& name : names)
	{
		const auto plugin = loader.create(name);
		out << "\n" << name << "    ([esif] plugin = " << name << ", parameters in [" << plugin->sectionName() << "])\n";
		for (const auto& p : plugin->parameters()) out << "  " << p.key << " = " << p.value << "\n      " << p.doc << "\n";
	}
	return out.str();
}

int pluginsCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd(
		"Lists the host's [esif] keys, the plugins found and their INI parameters, each with its default.", ' ',
		ESIF_VERSION);
	TCLAP::ValueArg<std::string> plugin_dir("", "plugin-dir", "extra folder to search for plugins", false, "", "DIR",
											cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;
	std::cout << pluginListing(plugin_dir.isSet() ? std::vector<std::string>{plugin_dir.getValue()}
												  : std::vector<std::string>{});
	return 0;
}

}  // namespace esif::app
