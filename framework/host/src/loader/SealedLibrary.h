#pragma once
/// \file SealedLibrary.h
/// A plugin file loaded so that nothing at its path can crash or hang esif.
/// dlopen() opens whatever the path names and maps it: a FIFO blocks it for
/// ever, and a file shorter than its program headers say (a copy or install
/// cut short) is mapped past its end, so the first touch of the missing part
/// kills the process with SIGBUS. Here the file is opened without blocking,
/// must be a regular file of at most kMaxLibraryBytes, and is copied into a
/// sealed memory file (memfd, F_SEAL_SHRINK | F_SEAL_WRITE | ...): no one can
/// shorten what is mapped. The copy's ELF header and program headers are then
/// checked (every segment inside the file), and only then is it loaded, by
/// its /proc/self/fd path. Its dependencies are found by their sonames among
/// the libraries the host has loaded and in the system's paths ($ORIGIN in a
/// plugin's runpath names /proc/self/fd). Where the process may not write a
/// file that large (RLIMIT_FSIZE, `ulimit -f`, holds for memory files too)
/// the file itself is checked and loaded through its open descriptor: a
/// file cut short is still refused, only one cut in the instant between the
/// check and the mapping is not.

#include <cstdint>
#include <string>

namespace esif
{
/// Largest plugin file loaded (esif's largest, ceres_full, is 4.4 MB).
inline constexpr std::uintmax_t kMaxLibraryBytes = std::uintmax_t{512} << 20;

struct LibraryLoad
{
	void* handle = nullptr;	 ///< dlopen's handle; null when it was not loaded
	std::string problem;  ///< why not, one line, naming no temporary path
};

/// Loads the library at `path` as above (RTLD_LAZY, as MRPT's
/// loadPluginModule did). Never throws for a bad file.
LibraryLoad loadSealedLibrary(const std::string& path);

}  // namespace esif
