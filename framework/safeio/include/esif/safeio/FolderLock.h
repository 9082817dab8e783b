#pragma once
/// \file FolderLock.h
/// An exclusive lock on an output folder for as long as one esif process
/// writes it, so a second run into the same --out fails at once instead of
/// both succeeding with a folder of mixed files. The lock is flock() on
/// `<parent>/.<name>.lock`, beside the folder rather than in it, because
/// the folder itself is replaced by a rename while locked.

#include <filesystem>
#include <string>

namespace esif
{
/// Whether to wait for a lock another process holds.
enum class LockWait
{
	No,	  ///< fail at once (a second run into the same --out)
	Yes,  ///< wait (jobs of a campaign that need the same simulation)
	Try	  ///< take it if it is free; held() says whether it was (a campaign job another process runs)
};

class FolderLock
{
   public:
	/// Takes the lock of `folder`. Throws InputError naming `folder` when
	/// another process holds it and `wait` is No ("another esif process is
	/// writing `what`"), or naming the lock file and the system's reason
	/// when it cannot be created (e.g. a read-only parent). The lock of a
	/// file set (FileSet.h) is that of its first file.
	explicit FolderLock(
		const std::filesystem::path& folder, LockWait wait = LockWait::No, const std::string& what = "this folder");
	/// Removes the lock file and releases the lock; never throws.
	~FolderLock();

	FolderLock(const FolderLock&) = delete;
	FolderLock& operator=(const FolderLock&) = delete;

	/// Whether this object holds the lock (false only after LockWait::Try
	/// found it held by another process).
	bool held() const { return fd_ >= 0; }

	/// `<parent>/.<name>.lock` for `folder`.
	static std::filesystem::path lockFileOf(const std::filesystem::path& folder);

   private:
	std::string path_;
	int fd_ = -1;
};

}  // namespace esif
