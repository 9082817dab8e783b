#pragma once
/// \file RunFolder.h
/// An output folder (of `esif run`, `compare`, `localmaps build`) written
/// all-or-nothing: everything goes into a hidden sibling
/// `.<name>.partial-<pid>`, which is checked and then swapped with --out in
/// one step (renameat2 RENAME_EXCHANGE, or a rename when --out is new), so
/// --out holds either the previous complete folder or the new complete one,
/// never a mixture or a part. The folder is locked (FolderLock.h) while
/// written, partial folders of killed writers are swept, and a signal
/// removes the partial folder (TerminationCleanup.h).
///
/// esif replaces only what it provably wrote: the folder's marker
/// `.esif-output` lists every file and folder the run put there, and a
/// later run replaces --out only while it holds nothing else. A folder
/// without the marker, or with one file the marker does not list, is the
/// user's: refused naming that file, nothing touched.

#include <esif/safeio/FolderLock.h>

#include <filesystem>
#include <string>
#include <vector>

namespace esif
{
/// The file that marks a folder as esif output and lists what esif wrote
/// there, so a later run may replace it.
inline constexpr const char* kOutputMarkerFile = ".esif-output";

class RunFolder
{
   public:
	/// Locks `target`, removes stale partial folders beside it, checks that
	/// it may be replaced (absent, empty, or esif output holding only what
	/// its marker lists; anything else is refused with an InputError naming
	/// the first file esif did not write) and creates the partial folder.
	explicit RunFolder(const std::string& target);
	/// Removes the partial folder (or, after commit, the previous folder if
	/// commit could not); never throws.
	~RunFolder();

	RunFolder(const RunFolder&) = delete;
	RunFolder& operator=(const RunFolder&) = delete;

	/// Where to write the outputs.
	std::string staging() const { return staging_.string(); }
	/// --out as given (normalised).
	std::string target() const { return target_.string(); }

	/// Checks that every file in `required` is present and not empty and no
	/// temporary file is left, writes the marker listing every entry,
	/// syncs the folder and swaps it into place; the previous folder is then
	/// removed.
	void commit(const std::vector<std::string>& required);

	/// Rethrows the exception being handled, of the same esif type, with the
	/// partial folder's path in its message replaced by --out's, so errors
	/// name the file as the user will look for it.
	[[noreturn]] void rethrowNamingTarget() const;

   private:
	std::filesystem::path target_;
	FolderLock lock_;
	std::filesystem::path staging_;
};

/// `.<name>.partial-<pid>` beside `target`: where this process stages a
/// new `target` before renaming it into place.
std::filesystem::path partialFolderOf(const std::filesystem::path& target);

/// Removes the partial folders of writers of `target` that were killed
/// (SIGKILL, power loss); call only while holding target's FolderLock,
/// under which no live writer owns one. Never throws.
void removeStalePartials(const std::filesystem::path& target);

/// Writes an output folder: `write(staging)` fills it, then it is committed
/// with `required`; returns what `write` returns. Errors name `target`.
template <class Write>
auto writeRunFolder(const std::string& target, const std::vector<std::string>& required, Write&& write)
{
	RunFolder folder(target);
	try
	{
		auto result = write(folder.staging());
		folder.commit(required);
		return result;
	}
	catch (...)
	{
		folder.rethrowNamingTarget();
	}
}

}  // namespace esif
