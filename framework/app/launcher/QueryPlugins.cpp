/// \file QueryPlugins.cpp
/// `esif_query_plugins`, a build tool: loads the plugins beside it as
/// `esif plugins` does and writes the plugin cache (PluginCache.h) into the
/// plugin folder, atomically. The build runs it whenever a plugin or an
/// esif library is rebuilt.

#include "../Commands.h"
#include "PluginCache.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
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
		const std::string cache = esif::launcher::cacheFileIn(lib);
		const std::string partial = cache + ".partial";
		{
			std::ofstream out(partial, std::ios::binary | std::ios::trunc);
			out << esif::launcher::cacheText(lib, before, listing);
			out.close();
			if (!out)
			{
				std::cerr << "esif_query_plugins: " << partial << ": cannot write\n";
				std::remove(partial.c_str());
				return 1;
			}
		}
		if (std::rename(partial.c_str(), cache.c_str()) != 0)
		{
			std::cerr << "esif_query_plugins: " << cache << ": cannot move into place\n";
			std::remove(partial.c_str());
			return 1;
		}
		return 0;
	}
	catch (const std::exception& e)
	{
		std::cerr << "esif_query_plugins: " << e.what() << "\n";
		return 1;
	}
}
