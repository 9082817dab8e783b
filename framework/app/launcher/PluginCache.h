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
/// What the listing depends on goes beyond esif's own files: a plugin that
/// loads only because of the system libraries it needs (Ceres, glog) lists
/// only while they load. So the cache also records the loader's environment
/// (LD_LIBRARY_PATH, LD_PRELOAD) and the size and time of every other
/// library the plugins brought in, and /etc/ld.so.cache; any change and the
/// host answers (and warns about a plugin that no longer loads).
///
/// File (text): "esif plugin cache 2", "folder <plugin folder>", one
/// "env NAME=VALUE" per loader variable, one "file <size> <mtime seconds>
/// <mtime nanoseconds> <name>" per esif library, one "dep <size> <mtime
/// seconds> <mtime nanoseconds> <absolute path>" per other library,
/// "listing <bytes>", then the listing itself. The launcher reads it only
/// when it is a regular file of at most kMaxCacheFileBytes (a FIFO or
/// /dev/zero in its place is not waited for nor read without end).

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

/// Largest cache file read: a listing is a few kilobytes per plugin, a
/// library's stamp a line.
inline constexpr std::uintmax_t kMaxCacheFileBytes = 8u << 20;

/// The host's libraries (`lib`/libesif_*.so) and the plugins
/// (`lib`/esif/libesif_plugin_*.so), sorted by name.
std::vector<FileStamp> stampLibraries(const std::string& lib);

/// Every library this process has loaded from outside `lib` (found with
/// dl_iterate_phdr: what the host and the plugins brought in), and
/// /etc/ld.so.cache, by absolute path, sorted.
std::vector<FileStamp> stampDependencies(const std::string& lib);

/// The stamps of the files `named` (absolute paths) as they are now; a file
/// that is gone gets size -1.
std::vector<FileStamp> restamp(const std::vector<FileStamp>& named);

/// "NAME=VALUE" for each variable of the dynamic loader that decides which
/// libraries load (unset and empty are the same).
std::vector<std::string> loaderEnvironment();

/// The cache's text for `listing` made with the libraries `stamps` in
/// `lib` and the other libraries `dependencies`, under loaderEnvironment().
std::string cacheText(const std::string& lib, const std::vector<FileStamp>& stamps,
					  const std::vector<FileStamp>& dependencies, const std::string& listing);

/// The cached listing if the cache file of `lib` exists, is a regular file
/// of at most kMaxCacheFileBytes, is well formed and was made from exactly
/// the libraries there now, with the same dependencies and loader
/// environment.
std::optional<std::string> cachedListing(const std::string& lib);

}  // namespace esif::launcher
