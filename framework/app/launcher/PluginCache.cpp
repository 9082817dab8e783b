/// \file PluginCache.cpp
/// See PluginCache.h. Only the C++ standard library and POSIX: the launcher
/// links nothing else.

#include "PluginCache.h"

#include <algorithm>
#include <dirent.h>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace esif::launcher
{
namespace
{
constexpr const char* kHeader = "esif plugin cache 1";
/// A listing is a few kilobytes per plugin.
constexpr std::uintmax_t kMaxCacheBytes = 4u << 20;

bool startsWith(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }
bool endsWith(const std::string& s, const std::string& suffix)
{
	return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
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

std::string cacheText(const std::string& lib, const std::vector<FileStamp>& stamps, const std::string& listing)
{
	std::ostringstream out;
	out << kHeader << "\n" << "folder " << lib << "\n";
	for (const auto& s : stamps) out << "file " << s.size << " " << s.mtime_s << " " << s.mtime_ns << " " << s.name << "\n";
	out << "listing " << listing.size() << "\n" << listing;
	return out.str();
}

std::optional<std::string> cachedListing(const std::string& lib)
{
	std::ifstream in(cacheFileIn(lib), std::ios::binary);
	if (!in) return std::nullopt;
	std::string line;
	if (!std::getline(in, line) || line != kHeader) return std::nullopt;
	if (!std::getline(in, line) || line != "folder " + lib) return std::nullopt;
	std::vector<FileStamp> cached;
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
		FileStamp s;
		if (tag != "file" || !(words >> s.size >> s.mtime_s >> s.mtime_ns) || !std::getline(words >> std::ws, s.name))
			return std::nullopt;
		if (cached.size() >= 10000) return std::nullopt;
		cached.push_back(std::move(s));
	}
	if (listing_bytes == 0 || cached != stampLibraries(lib)) return std::nullopt;
	std::string listing(listing_bytes, '\0');
	if (!in.read(listing.data(), static_cast<std::streamsize>(listing_bytes)) || in.peek() != EOF) return std::nullopt;
	return listing;
}

}  // namespace esif::launcher
