/// \file PluginCache.cpp
/// See PluginCache.h. Only the C++ standard library and POSIX: the launcher
/// links nothing else.

#include "PluginCache.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <dirent.h>
#include <fcntl.h>
#include <link.h>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace esif::launcher
{
namespace
{
constexpr const char* kHeader = "esif plugin cache 2";
/// A listing is a few kilobytes per plugin.
constexpr std::uintmax_t kMaxCacheBytes = 4u << 20;
/// Most libraries a cache lists (the host brings some 300).
constexpr std::size_t kMaxStamps = 10000;
/// The dynamic loader's variables that change which libraries load.
constexpr const char* kLoaderVariables[] = {"LD_LIBRARY_PATH", "LD_PRELOAD"};

bool startsWith(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }
bool endsWith(const std::string& s, const std::string& suffix)
{
	return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// The stamp of `path` named `name`; size -1 when it cannot be stat()ed.
FileStamp stampOf(const std::string& path, const std::string& name)
{
	struct stat st
	{
	};
	if (::stat(path.c_str(), &st) != 0) return {name, static_cast<std::uintmax_t>(-1), 0, 0};
	return {name, static_cast<std::uintmax_t>(st.st_size), st.st_mtim.tv_sec, st.st_mtim.tv_nsec};
}

/// The whole of `path` when it is a regular file of at most `max_bytes`;
/// opened without blocking (a FIFO) and read no further than its size said.
std::optional<std::string> readBoundedFile(const std::string& path, std::uintmax_t max_bytes)
{
	const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
	if (fd < 0) return std::nullopt;
	struct stat st
	{
	};
	std::optional<std::string> bytes;
	if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && static_cast<std::uintmax_t>(st.st_size) <= max_bytes)
	{
		std::string buffer(static_cast<std::size_t>(st.st_size), '\0');
		std::size_t done = 0;
		for (ssize_t n = 1; done < buffer.size() && n != 0;)
		{
			n = ::read(fd, buffer.data() + done, buffer.size() - done);
			if (n < 0 && errno != EINTR) break;
			if (n > 0) done += static_cast<std::size_t>(n);
		}
		if (done == buffer.size()) bytes = std::move(buffer);
	}
	::close(fd);
	return bytes;
}

/// Reads "TAG <size> <mtime s> <mtime ns> <name>" (the tag already read).
bool readStamp(std::istringstream& words, FileStamp& s)
{
	return static_cast<bool>(words >> s.size >> s.mtime_s >> s.mtime_ns) && std::getline(words >> std::ws, s.name);
}

/// Appends the stamps of `folder`'s files named prefix*.so, named
/// `relative` + file name.
void stampFolder(const std::string& folder, const std::string& relative, const std::string& prefix,
				 std::vector<FileStamp>& stamps)
{
	DIR* dir = ::opendir(folder.c_str());
	if (!dir) return;
	while (const dirent* entry = ::readdir(dir))
	{
		const std::string name = entry->d_name;
		if (!startsWith(name, prefix) || !endsWith(name, ".so")) continue;
		struct stat st
		{
		};
		if (::stat((folder + "/" + name).c_str(), &st) != 0 || !S_ISREG(st.st_mode)) continue;
		stamps.push_back({relative + name, static_cast<std::uintmax_t>(st.st_size), st.st_mtim.tv_sec, st.st_mtim.tv_nsec});
	}
	::closedir(dir);
}
}  // namespace

std::string libFolderBesideExecutable()
{
	char path[4096];
	const ssize_t n = ::readlink("/proc/self/exe", path, sizeof(path) - 1);
	if (n <= 0) return {};
	std::string exe(path, static_cast<std::size_t>(n));
	const auto bin = exe.rfind('/');
	if (bin == std::string::npos) return {};
	const auto prefix = exe.rfind('/', bin == 0 ? 0 : bin - 1);
	if (prefix == std::string::npos) return {};
	return exe.substr(0, prefix) + "/lib";
}

std::string cacheFileIn(const std::string& lib) { return lib + "/esif/plugins.cache"; }

std::vector<FileStamp> stampLibraries(const std::string& lib)
{
	std::vector<FileStamp> stamps;
	stampFolder(lib, "", "libesif_", stamps);
	stampFolder(lib + "/esif", "esif/", "libesif_plugin_", stamps);
	std::sort(stamps.begin(), stamps.end(), [](const FileStamp& a, const FileStamp& b) { return a.name < b.name; });
	return stamps;
}

std::vector<FileStamp> stampDependencies(const std::string& lib)
{
	std::vector<std::string> paths{"/etc/ld.so.cache"};
	const auto collect = [](dl_phdr_info* info, std::size_t, void* data) {
		const std::string name = info->dlpi_name ? info->dlpi_name : "";
		// The program itself and the vDSO have no path; plugins are loaded
		// from sealed copies (/proc/self/fd/N) and stamped as esif's own.
		if (!name.empty() && name[0] == '/' && name.rfind("/proc/", 0) != 0)
			static_cast<std::vector<std::string>*>(data)->push_back(name);
		return 0;
	};
	::dl_iterate_phdr(collect, &paths);
	char* real_lib = ::realpath(lib.c_str(), nullptr);
	const std::string own = std::string(real_lib ? real_lib : lib.c_str()) + "/";
	std::free(real_lib);
	std::vector<FileStamp> stamps;
	for (const auto& p : paths)
	{
		// Loaded through RUNPATH $ORIGIN/../lib: compared by its real path.
		char* real = ::realpath(p.c_str(), nullptr);
		const std::string path = real ? real : p;
		std::free(real);
		if (path.rfind(own, 0) != 0) stamps.push_back(stampOf(path, path));	 // esif's own: stampLibraries
	}
	std::sort(stamps.begin(), stamps.end(), [](const FileStamp& a, const FileStamp& b) { return a.name < b.name; });
	stamps.erase(std::unique(stamps.begin(), stamps.end()), stamps.end());
	return stamps;
}

std::vector<FileStamp> restamp(const std::vector<FileStamp>& named)
{
	std::vector<FileStamp> now;
	for (const auto& s : named) now.push_back(stampOf(s.name, s.name));
	return now;
}

std::vector<std::string> loaderEnvironment()
{
	std::vector<std::string> out;
	for (const char* name : kLoaderVariables)
	{
		const char* value = std::getenv(name);
		out.push_back(std::string(name) + "=" + (value ? value : ""));
	}
	return out;
}

std::string cacheText(const std::string& lib, const std::vector<FileStamp>& stamps,
					  const std::vector<FileStamp>& dependencies, const std::string& listing)
{
	std::ostringstream out;
	out << kHeader << "\n" << "folder " << lib << "\n";
	for (const auto& e : loaderEnvironment()) out << "env " << e << "\n";
	for (const auto& s : stamps) out << "file " << s.size << " " << s.mtime_s << " " << s.mtime_ns << " " << s.name << "\n";
	for (const auto& s : dependencies)
		out << "dep " << s.size << " " << s.mtime_s << " " << s.mtime_ns << " " << s.name << "\n";
	out << "listing " << listing.size() << "\n" << listing;
	return out.str();
}

std::optional<std::string> cachedListing(const std::string& lib)
{
	const auto bytes = readBoundedFile(cacheFileIn(lib), kMaxCacheFileBytes);
	if (!bytes) return std::nullopt;
	std::istringstream in(*bytes);
	std::string line;
	if (!std::getline(in, line) || line != kHeader) return std::nullopt;
	if (!std::getline(in, line) || line != "folder " + lib) return std::nullopt;
	std::vector<FileStamp> cached, dependencies;
	std::vector<std::string> environment;
	std::uintmax_t listing_bytes = 0;
	while (std::getline(in, line))
	{
		std::istringstream words(line);
		std::string tag;
		words >> tag;
		if (tag == "listing")
		{
			if (!(words >> listing_bytes) || listing_bytes > kMaxCacheBytes) return std::nullopt;
			break;
		}
		if (cached.size() + dependencies.size() + environment.size() >= kMaxStamps) return std::nullopt;
		FileStamp s;
		if (tag == "env")
			environment.push_back(line.substr(4));
		else if (tag == "file" && readStamp(words, s))
			cached.push_back(std::move(s));
		else if (tag == "dep" && readStamp(words, s))
			dependencies.push_back(std::move(s));
		else
			return std::nullopt;
	}
	if (listing_bytes == 0 || environment != loaderEnvironment() || cached != stampLibraries(lib) ||
		dependencies != restamp(dependencies))
		return std::nullopt;
	const auto at = static_cast<std::size_t>(in.tellg());
	if (in.fail() || bytes->size() - at != listing_bytes) return std::nullopt;
	return bytes->substr(at);
}

}  // namespace esif::launcher
