/// \file CheckedWrite.cpp
/// POSIX write loop with every result checked; see CheckedWrite.h.

#include <esif/core/Errors.h>
#include <esif/safeio/CheckedFileWriter.h>
#include "CheckedWrite.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>
#include <utility>

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
void writeAll(int fd, const char* data, std::size_t size, const std::string& shown_name)
{
	std::size_t done = 0;
	while (done < size)
	{
		const ssize_t n = ::write(fd, data + done, size - done);
		if (n < 0 && errno == EINTR) continue;
		if (n < 0) fail(shown_name, "write", errno);
		done += static_cast<std::size_t>(n);
	}
}
}  // namespace

CheckedFileWriter::CheckedFileWriter(const std::string& path, std::string shown_name)
	: shown_name_(std::move(shown_name))
{
	fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
	if (fd_ < 0) fail(shown_name_, "open", errno);
}

CheckedFileWriter::~CheckedFileWriter()
{
	if (fd_ >= 0) ::close(fd_);
}

void CheckedFileWriter::write(const void* data, std::size_t size)
{
	writeAll(fd_, static_cast<const char*>(data), size, shown_name_);
}

void CheckedFileWriter::finish()
{
	// Delayed allocation (ext4, xfs, NFS) may report ENOSPC or EDQUOT only at
	// fsync or close: both are checked, not just the writes.
	const int fd = fd_;
	fd_ = -1;
	if (::fsync(fd) != 0)
	{
		const int err = errno;
		::close(fd);
		fail(shown_name_, "fsync", err);
	}
	if (::close(fd) != 0) fail(shown_name_, "close", errno);
}

void writeBytesChecked(const std::string& path, const std::string& bytes, const std::string& shown_name)
{
	CheckedFileWriter file(path, shown_name);
	file.write(bytes.data(), bytes.size());
	file.finish();
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
