#pragma once
/// \file PluginCache.h
/// A cache of what `esif plugins` prints, so that the launcher answers it
/// without loading the host, MRPT and every plugin (about 0.15 s of dynamic
/// linking). The same idea as GIO's giomodule.cache (gio-querymodules) and
/// gdk-pixbuf's loaders.cache: a build tool (QueryPlugins.cpp) loads the
/// plugins once and writes the listing beside them, together with the size
/// and modification time of every library it depends on; the launcher uses
/// it only while every one of those files is unchanged and nothing was added
/// or removed, and otherwise loads the host as for any command.
///
/// File (text): "esif plugin cache 1", "folder <plugin folder>", one
/// "file <size> <mtime seconds> <mtime nanoseconds> <name>" per library,
/// "listing <bytes>", then the listing itself.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace esif::launcher
{
/// One library the listing depends on, as stat() sees it.
struct FileStamp
{
	std::string name;  ///< relative to the lib folder: "libesif_host.so", "esif/libesif_plugin_ekf.so"
	std::uintmax_t size = 0;
	std::int64_t mtime_s = 0;
	std::int64_t mtime_ns = 0;
	bool operator==(const FileStamp& o) const
	{
		return name == o.name && size == o.size && mtime_s == o.mtime_s && mtime_ns == o.mtime_ns;
	}
};

/// The lib folder beside the running executable (bin/../lib); empty when
/// /proc/self/exe cannot be read.
std::string libFolderBesideExecutable();

/// The cache file in the plugin folder `lib`/esif.
std::string cacheFileIn(const std::string& lib);

/// The host's libraries (`lib`/libesif_*.so) and the plugins
/// (`lib`/esif/libesif_plugin_*.so), sorted by name.
std::vector<FileStamp> stampLibraries(const std::string& lib);

/// The cache's text for `listing` made with the libraries `stamps` in `lib`.
std::string cacheText(const std::string& lib, const std::vector<FileStamp>& stamps, const std::string& listing);

/// The cached listing if the cache file of `lib` exists, is well formed
/// (bounded) and was made from exactly the libraries there now.
std::optional<std::string> cachedListing(const std::string& lib);

}  // namespace esif::launcher
