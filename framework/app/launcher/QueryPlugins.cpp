/// \file QueryPlugins.cpp
/// `esif_query_plugins`, a build tool: loads the plugins beside it as
/// `esif plugins` does and writes the plugin cache (PluginCache.h) into the
/// plugin folder, atomically. The build runs it whenever a plugin or an
/// esif library is rebuilt.

#include "../Commands.h"
#include "PluginCache.h"

#include <esif/safeio/AtomicFile.h>

#include <cstdlib>
#include <iostream>

int main(int argc, char** argv)
{
	if (argc != 1)
	{
		std::cerr << "usage: esif_query_plugins (writes ../lib/esif/plugins.cache beside itself)\n";
		return 2;
	}
	try
	{
		// The cache answers only for the folder beside the executable.
		::unsetenv("ESIF_PLUGIN_PATH");
		const std::string lib = esif::launcher::libFolderBesideExecutable();
		const auto before = esif::launcher::stampLibraries(lib);
		const std::string listing = esif::app::pluginListing({});
		if (esif::launcher::stampLibraries(lib) != before)
		{
			std::cerr << "esif_query_plugins: the libraries in " << lib << " changed while they were listed\n";
			return 1;
		}
		// Every other library the plugins brought in: the listing holds only while they load.
		const auto dependencies = esif::launcher::stampDependencies(lib);
		// Checked, synced and renamed into place like every esif output.
		esif::writeTextAtomically(
			esif::launcher::cacheFileIn(lib), esif::launcher::cacheText(lib, before, dependencies, listing));
		return 0;
	}
	catch (const std::exception& e)
	{
		std::cerr << "esif_query_plugins: " << e.what() << "\n";
		return 1;
	}
}
