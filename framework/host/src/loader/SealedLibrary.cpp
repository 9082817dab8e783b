/// \file SealedLibrary.cpp
/// Copy, seal, check, load; see SealedLibrary.h.

#include "SealedLibrary.h"

#include <esif/core/Text.h>

#include <cerrno>
#include <cstring>
#include <dlfcn.h>
#include <elf.h>
#include <fcntl.h>
#include <map>
#include <mutex>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace esif
{
namespace
{
/// A descriptor closed when it goes out of scope, unless released.
class OwnedFd
{
   public:
	explicit OwnedFd(int fd) : fd_(fd) {}
	~OwnedFd()
	{
		if (fd_ >= 0) ::close(fd_);
	}
	OwnedFd(const OwnedFd&) = delete;
	OwnedFd& operator=(const OwnedFd&) = delete;
	OwnedFd& operator=(OwnedFd&& other) noexcept
	{
		if (fd_ >= 0) ::close(fd_);
		fd_ = other.release();
		return *this;
	}
	int get() const { return fd_; }
	int release()
	{
		const int fd = fd_;
		fd_ = -1;
		return fd;
	}

   private:
	int fd_;
};

std::string systemError(const char* step) { return std::string(step) + ": " + std::strerror(errno); }

/// Copies the `size` bytes of `from` into `to`: 0, an errno value, or -1
/// when the file's size changed while it was read.
int copyWhole(int from, int to, std::uintmax_t size)
{
	std::vector<char> buffer(1 << 16);
	std::uintmax_t done = 0;
	for (;;)
	{
		const ssize_t n = ::read(from, buffer.data(), buffer.size());
		if (n < 0 && errno == EINTR) continue;
		if (n < 0) return errno;
		if (n == 0) break;
		for (ssize_t put = 0; put < n;)
		{
			const ssize_t w = ::write(to, buffer.data() + put, static_cast<std::size_t>(n - put));
			if (w < 0 && errno == EINTR) continue;
			if (w < 0) return errno;
			put += w;
		}
		done += static_cast<std::uintmax_t>(n);
		if (done > size) break;
	}
	return done == size ? 0 : -1;
}

/// The descriptor to check and load: a sealed copy of `file`, or, when the
/// process may not write one that large (RLIMIT_FSIZE, `ulimit -f`, holds
/// for memory files too), `file` itself, checked in place. "" or the problem.
std::string imageOf(OwnedFd& file, std::uintmax_t size, OwnedFd& image)
{
	OwnedFd sealed(::memfd_create("esif-plugin", MFD_CLOEXEC | MFD_ALLOW_SEALING));
	if (sealed.get() < 0) return systemError("memfd_create");
	const int copied = copyWhole(file.get(), sealed.get(), size);
	if (copied == EFBIG)
	{
		image = OwnedFd(file.release());
		return "";
	}
	if (copied == -1) return "its size changed while it was read (a copy or install in progress?)";
	if (copied != 0) return std::string("copy: ") + std::strerror(copied);
	if (::fcntl(sealed.get(), F_ADD_SEALS, F_SEAL_SHRINK | F_SEAL_GROW | F_SEAL_WRITE | F_SEAL_SEAL) != 0)
		return systemError("seal");
	image = OwnedFd(sealed.release());
	return "";
}

/// Why the ELF image `bytes` (`size` of them) cannot be mapped as it says,
/// or "": a 64-bit shared object of this machine whose program headers, and
/// every segment they describe, lie inside the file.
std::string elfProblem(const unsigned char* bytes, std::uintmax_t size)
{
	if (size < sizeof(Elf64_Ehdr) || std::memcmp(bytes, ELFMAG, SELFMAG) != 0) return "not an ELF file";
	Elf64_Ehdr header;
	std::memcpy(&header, bytes, sizeof(header));
	if (header.e_ident[EI_CLASS] != ELFCLASS64 || header.e_type != ET_DYN) return "not a 64-bit shared library";
	const std::uintmax_t table_end =
		static_cast<std::uintmax_t>(header.e_phoff) + std::uintmax_t{header.e_phnum} * sizeof(Elf64_Phdr);
	if (header.e_phentsize != sizeof(Elf64_Phdr) || header.e_phoff > size || table_end > size)
		return "cut short: its program headers lie beyond its " + std::to_string(size) + " bytes";
	for (unsigned i = 0; i < header.e_phnum; ++i)
	{
		Elf64_Phdr segment;
		std::memcpy(&segment, bytes + header.e_phoff + i * sizeof(Elf64_Phdr), sizeof(segment));
		if (segment.p_offset > size || segment.p_filesz > size - segment.p_offset)
			return "cut short: segment " + std::to_string(i) + " ends at byte " +
				   std::to_string(static_cast<std::uintmax_t>(segment.p_offset) + segment.p_filesz) +
				   ", the file has " + std::to_string(size);
	}
	return "";
}

/// The libraries loaded so far, by the file they were copied from (device,
/// inode): each is loaded once per process, as dlopen of one path would, so
/// its classes register once however many PluginLoaders ask for it. Their
/// sealed copies stay open for the process's life: dlopen knows a library by
/// the name it was opened with, so a /proc/self/fd/N used again for another
/// plugin would be taken for the first one.
struct Loaded
{
	std::mutex mutex;
	std::map<std::pair<dev_t, ino_t>, void*> handles;
};

Loaded& loaded()
{
	static Loaded l;
	return l;
}
}  // namespace

LibraryLoad loadSealedLibrary(const std::string& path)
{
	OwnedFd file(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
	if (file.get() < 0) return {nullptr, systemError("open")};
	struct stat st{};
	if (::fstat(file.get(), &st) != 0) return {nullptr, systemError("stat")};
	if (!S_ISREG(st.st_mode)) return {nullptr, "not a regular file (a FIFO, device or folder is never loaded)"};
	const auto size = static_cast<std::uintmax_t>(st.st_size);
	const std::lock_guard<std::mutex> lock(loaded().mutex);
	if (const auto it = loaded().handles.find({st.st_dev, st.st_ino}); it != loaded().handles.end())
		return {it->second, ""};
	if (size > kMaxLibraryBytes)
		return {nullptr, std::to_string(size) + " bytes, more than a plugin holds (" + std::to_string(kMaxLibraryBytes) + ")"};

	OwnedFd image(-1);
	if (const std::string problem = imageOf(file, size, image); !problem.empty()) return {nullptr, problem};
	if (size < sizeof(Elf64_Ehdr)) return {nullptr, "not an ELF file"};
	void* mapped = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, image.get(), 0);
	if (mapped == MAP_FAILED) return {nullptr, systemError("mmap")};
	const std::string problem = elfProblem(static_cast<const unsigned char*>(mapped), size);
	::munmap(mapped, size);
	if (!problem.empty()) return {nullptr, problem};

	const std::string proc_path = "/proc/self/fd/" + std::to_string(image.get());
	void* handle = ::dlopen(proc_path.c_str(), RTLD_LAZY);
	if (!handle)
	{
		const char* why = ::dlerror();
		std::string text = why ? why : "no reason given";
		text = replaceAll(replaceAll(text, proc_path + ": ", ""), proc_path, path);
		return {nullptr, "dlerror: " + text};
	}
	image.release();  // kept open: see loaded()
	loaded().handles[{st.st_dev, st.st_ino}] = handle;
	return {handle, ""};
}

}  // namespace esif
