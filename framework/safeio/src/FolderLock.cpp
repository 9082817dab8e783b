/// \file FolderLock.cpp
/// flock() with the unlink race handled; see FolderLock.h.

#include <esif/core/Errors.h>
#include <esif/safeio/FolderLock.h>
#include <esif/safeio/TerminationCleanup.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace esif
{
namespace
{
/// Whether `fd` is still the file named `path`: the holder before us
/// unlinks the lock file when it ends, so a lock taken on a file opened
/// just before that unlink locks nothing anyone else will see.
bool stillNamed(int fd, const std::string& path)
{
	struct stat held{}, named{};
	if (::fstat(fd, &held) != 0 || ::stat(path.c_str(), &named) != 0) return false;
	return held.st_dev == named.st_dev && held.st_ino == named.st_ino;
}
}  // namespace

std::filesystem::path FolderLock::lockFileOf(const std::filesystem::path& folder)
{
	return folder.parent_path() / ("." + folder.filename().string() + ".lock");
}

FolderLock::FolderLock(const std::filesystem::path& folder, LockWait wait, const std::string& what)
	: path_(lockFileOf(folder).string())
{
	for (;;)
	{
		fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
		if (fd_ < 0)
			throw InputError(folder.string() + ": cannot create the lock file " + path_ + ": " + std::strerror(errno));
		int locked;
		do
			locked = ::flock(fd_, LOCK_EX | (wait == LockWait::Yes ? 0 : LOCK_NB));
		while (locked != 0 && errno == EINTR);
		if (locked != 0)
		{
			const int err = errno;
			::close(fd_);
			fd_ = -1;
			if (err == EWOULDBLOCK && wait == LockWait::Try) return;
			if (err == EWOULDBLOCK)
				throw InputError(folder.string() + ": another esif process is writing " + what + " (lock " + path_ +
								 " is held); wait for it or choose another --out");
			throw InputError(folder.string() + ": cannot lock " + path_ + ": " + std::strerror(err));
		}
		if (stillNamed(fd_, path_)) break;
		::close(fd_);
	}
	termination::addPath(path_);
}

FolderLock::~FolderLock()
{
	if (fd_ < 0) return;
	// Unlinked while still held, so a process waiting for it finds the file
	// gone (stillNamed) and starts again on a fresh one.
	termination::removePath(path_);
	::unlink(path_.c_str());
	::close(fd_);
}

}  // namespace esif
