#pragma once
/// \file FileSet.h
/// Output files that live among other files (a rawlog and the ground truth
/// beside it, a g2o file, a job list, a campaign's summary files): the
/// counterpart of RunFolder.h for files, under the same two rules.
///
/// A file esif did not write is never replaced. How esif knows it wrote
/// one: each set keeps a record beside its files, `.<first file>.esif-files`,
/// listing every file it put there with its size and CRC-32 and the kind of
/// output the set is. A file at an output's name may be replaced only while
/// the record of that output lists it, for the same kind, with the size and
/// CRC it has now: a file esif did not write, or one the user changed since,
/// is refused naming it, and nothing is touched. (A record beside a file
/// proves no more than the folder marker does; both are about not
/// destroying data by accident, not about an adversary.)
///
/// Related files are committed together or not at all: they are written
/// into a partial folder beside them (`.<first file>.partial-<pid>`, like a
/// run folder's), and only when all are written is the set committed, under
/// the set's lock (FolderLock.h) and with the termination watcher held off:
/// the record is rewritten first, saying "committing" and what the set will
/// be, then each file is renamed into place, files of the previous set that
/// the new one does not have are removed, and the record says "complete".
/// A process killed (SIGKILL, power loss) between the renames leaves a
/// "committing" record: readers refuse the set (requireCompleteFileSet), and
/// the next writer of the set first finishes the commit from the partial
/// folder (the renames are repeated, never undone).

#include <esif/safeio/FolderLock.h>
#include <esif/safeio/OutputApart.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
class FileSet
{
   public:
	/// Claims `files` (paths in one folder, the first naming the set) for an
	/// output of `kind` ("a rawlog and its ground truth"): checks that none
	/// overlaps one of `inputs` (OutputApart.h), creates the folder, takes
	/// the set's lock, finishes a commit a killed writer left, removes
	/// partial folders of killed writers, checks that each file is absent
	/// or esif's (see above; InputError naming the first that is not) and
	/// creates the partial folder.
	FileSet(std::string kind, const std::vector<std::string>& files, const std::vector<NamedInput>& inputs = {});
	/// Removes the partial folder; never throws.
	~FileSet();

	FileSet(const FileSet&) = delete;
	FileSet& operator=(const FileSet&) = delete;

	/// Where to write `file` (one of the set's files, as given): the same
	/// name in the partial folder.
	std::string staging(const std::string& file) const;
	/// The partial folder, for writers that put several files into a folder.
	std::string stagingFolder() const { return staging_.string(); }

	/// Commits what the partial folder holds (each a file of the set; a file
	/// of the set not written is not part of the new set, and is removed if
	/// the previous one had it). InputError naming the file on any failure.
	void commit();

	/// Rethrows the exception being handled, of the same esif type, with the
	/// partial folder in its message replaced by the folder of the files.
	[[noreturn]] void rethrowNamingTargets() const;

   private:
	std::string kind_;
	std::filesystem::path folder_;
	std::vector<std::string> names_;  ///< file names in folder_, the first naming the set
	std::filesystem::path first_;	  ///< folder_ / names_[0]
	std::optional<FolderLock> lock_;
	std::filesystem::path staging_;
};

/// Writes a set: `write(set)` writes its files at set.staging(file) (or
/// into set.stagingFolder()), then the set is committed; returns what
/// `write` returns. Errors name the files where the user will look for them.
template <class Write>
auto writeFileSet(
	const std::string& kind, const std::vector<std::string>& files, const std::vector<NamedInput>& inputs,
	Write&& write)
{
	FileSet set(kind, files, inputs);
	try
	{
		auto result = write(set);
		set.commit();
		return result;
	}
	catch (...)
	{
		set.rethrowNamingTargets();
	}
}

/// Throws InputError naming `file` when the set it is the first file of was
/// left half-committed (its record says "committing"): the files beside it
/// do not belong together until that set is written again.
void requireCompleteFileSet(const std::string& file);

/// `.<name>.esif-files` beside `first`: the record of the set it names.
std::filesystem::path fileSetRecordOf(const std::filesystem::path& first);

}  // namespace esif
