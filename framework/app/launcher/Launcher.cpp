/// \file Launcher.cpp
/// The `esif` executable. It answers `esif --help` itself and `esif
/// plugins` from the plugin cache (PluginCache.h) while that is current, and
/// hands every other command line to the host, libesif_app.so, which it
/// loads from ../lib beside itself. Loading the host binds some 300 shared
/// objects (MRPT's Debian libraries, OpenCV and theirs), about 0.15 s before
/// any work; `esif --help` and `esif plugins` answered here take a few
/// milliseconds. The launcher links only the C++ runtime.

#include "../CommandList.h"
#include "PluginCache.h"

#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <iostream>
#include <string>

namespace
{
using AppMain = int (*)(int, char**);

/// The cache serves `esif plugins` alone: no option, no extra plugin folder
/// from the environment, and not when ESIF_PLUGIN_CACHE=0 asks to bypass it.
bool cacheMayAnswer(int argc, char** argv)
{
	if (argc != 2 || std::strcmp(argv[1], "plugins") != 0) return false;
	const char* extra = std::getenv("ESIF_PLUGIN_PATH");
	const char* bypass = std::getenv("ESIF_PLUGIN_CACHE");
	return (!extra || !*extra) && !(bypass && std::strcmp(bypass, "0") == 0);
}

/// Loads the host and runs the command line through it.
int runHost(const std::string& lib, int argc, char** argv)
{
	const std::string host = lib + "/libesif_app.so";
	// RTLD_GLOBAL: the host's libraries are visible to the plugins it loads,
	// as when they were linked into the executable. RTLD_LAZY, as the
	// dynamic loader binds an executable's own libraries: RTLD_NOW made the
	// start 25 ms (16%) slower than linking the host into the executable,
	// lazy binding is within 3% of it.
	void* handle = ::dlopen(host.c_str(), RTLD_LAZY | RTLD_GLOBAL);
	if (!handle)
	{
		const char* why = ::dlerror();
		std::cerr << "esif: internal error: cannot load the host " << host << ": " << (why ? why : "no reason given")
				  << "\n";
		return 4;
	}
	const auto app_main = reinterpret_cast<AppMain>(::dlsym(handle, "esif_app_main"));
	if (!app_main)
	{
		std::cerr << "esif: internal error: " << host << " has no esif_app_main\n";
		return 4;
	}
	return app_main(argc, argv);
}
}  // namespace

int main(int argc, char** argv)
{
	if (argc == 2 && esif::app::isHelpRequest(argv[1]))
	{
		esif::app::printUsage(std::cout);
		return 0;
	}
	const std::string lib = esif::launcher::libFolderBesideExecutable();
	if (cacheMayAnswer(argc, argv))
		if (const auto listing = esif::launcher::cachedListing(lib))
		{
			std::cout << *listing << std::flush;
			return std::cout ? 0 : 1;
		}
	return runHost(lib, argc, argv);
}
