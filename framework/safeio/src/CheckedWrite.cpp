/// \file CheckedWrite.cpp
/// POSIX write loop with every result checked; see CheckedWrite.h.

#include <esif/core/Errors.h>
#include "CheckedWrite.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace esif
{
namespace
{
[[noreturn]] void fail(const std::string& shown_name, const char* step, int err)
{
	throw InputError(shown_name + ": cannot write (" + step + "): " + std::strerror(err));
}

/// write() until every byte is out: it may write less than asked (signals,
/// pipes, quotas) and that is not an error by itself, only -1 is.
void writeAll(int fd, const std::string& bytes, const std::string& shown_name)
{
	std::size_t done = 0;
	while (done < bytes.size())
	{
		const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
		if (n < 0 && errno == EINTR) continue;
		if (n < 0)
		{
			const int err = errno;
			::close(fd);
			fail(shown_name, "write", err);
		}
		done += static_cast<std::size_t>(n);
	}
}
}  // namespace

void writeBytesChecked(const std::string& path, const std::string& bytes, const std::string& shown_name)
{
	const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
	if (fd < 0) fail(shown_name, "open", errno);
	writeAll(fd, bytes, shown_name);
	// Delayed allocation (ext4, xfs, NFS) may report ENOSPC or EDQUOT only at
	// fsync or close: both are checked, not just the writes.
	if (::fsync(fd) != 0)
	{
		const int err = errno;
		::close(fd);
		fail(shown_name, "fsync", err);
	}
	if (::close(fd) != 0) fail(shown_name, "close", errno);
}

void syncFolder(const std::string& dir)
{
	const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
	if (fd < 0) throw InputError(dir + ": cannot open folder to sync it: " + std::strerror(errno));
	const bool ok = ::fsync(fd) == 0;
	const int err = errno;
	::close(fd);
	if (!ok) throw InputError(dir + ": cannot sync folder: " + std::strerror(err));
}

}  // namespace esif
