/// \file FileSet.cpp
/// Claiming, writing and committing a set of output files; see FileSet.h.

#include <esif/safeio/FileSet.h>

#include "CheckedWrite.h"
#include "FileSetRecord.h"

#include <esif/core/Errors.h>
#include <esif/core/TextInput.h>
#include <esif/safeio/AtomicFile.h>
#include <esif/safeio/RunFolder.h>
#include <esif/safeio/TerminationCleanup.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <unistd.h>

namespace fs = std::filesystem;

namespace esif
{
namespace
{
fs::path folderOf(const fs::path& file) { return file.parent_path().empty() ? fs::path(".") : file.parent_path(); }

/// The file names of `files`, which must share one folder and be distinct.
std::vector<std::string> namesIn(const fs::path& folder, const std::vector<std::string>& files)
{
	std::vector<std::string> names;
	for (const auto& f : files)
	{
		const fs::path p = fs::path(f).lexically_normal();
		if (folderOf(p) != folder) throw InputError(f + ": not in the folder of " + files.front());
		if (!isRecordableName(p.filename().string()))
			throw InputError(
				f + ": the file name holds a control character: esif's record of the files it wrote is one name "
					"per line; choose another name");
		if (std::find(names.begin(), names.end(), p.filename().string()) != names.end())
			throw InputError(f + ": given twice as an output");
		names.push_back(p.filename().string());
	}
	return names;
}

/// Writes the record at `path` through a temporary name and a rename. Not
/// AtomicFile.h: it runs while the termination watcher is held off, and
/// registering the temporary file with it would wait for that very hold.
void writeRecord(const fs::path& path, const FileSetRecord& record)
{
	const fs::path tmp = path.string() + "." + std::to_string(::getpid()) + ".tmp";
	writeBytesChecked(tmp.string(), record.text(), path.string());
	if (std::rename(tmp.c_str(), path.c_str()) != 0)
	{
		const int err = errno;
		std::remove(tmp.c_str());
		throw InputError(path.string() + ": cannot write: " + std::strerror(err));
	}
}

/// Removes the temporary records a killed writer left (`RECORD.<pid>.tmp`);
/// call under the set's lock. Never throws.
void removeStaleRecordCopies(const fs::path& record_path)
{
	const std::string prefix = record_path.filename().string() + ".";
	std::error_code ec;
	for (fs::directory_iterator it(record_path.parent_path(), ec), end; !ec && it != end; it.increment(ec))
	{
		const std::string name = it->path().filename().string();
		if (name.size() <= prefix.size() + 4 || name.compare(0, prefix.size(), prefix) != 0 ||
			name.compare(name.size() - 4, 4, ".tmp") != 0)
			continue;
		const std::string pid = name.substr(prefix.size(), name.size() - prefix.size() - 4);
		if (std::all_of(pid.begin(), pid.end(), [](unsigned char c) { return std::isdigit(c); }))
		{
			std::error_code ignored;
			fs::remove(it->path(), ignored);
		}
	}
}

/// Renames each file of a committing `record` from its partial folder into
/// place and removes the previous set's files it lists.
void moveIntoPlace(const fs::path& folder, const FileSetRecord& record)
{
	for (const auto& e : record.files)
	{
		const fs::path staged = folder / record.committing_from / e.name, target = folder / e.name;
		if (std::rename(staged.c_str(), target.c_str()) != 0)
			throw InputError(target.string() + ": cannot move the new file into place: " + std::strerror(errno));
	}
	for (const auto& e : record.removed)
		if (::unlink((folder / e.name).c_str()) != 0 && errno != ENOENT)
			throw InputError((folder / e.name).string() + ": cannot remove the previous file: " + std::strerror(errno));
	syncFolder(folder.string());
}

/// What a writer killed between the renames left: the renames still to do
/// are done (a file whose partial copy is gone stays as it is), the previous
/// files still there are removed, and the record becomes complete, listing
/// the files that are now as it says: a file that could not be finished is
/// no longer esif's to replace.
FileSetRecord finishKilledCommit(const fs::path& folder, const fs::path& record_path, const FileSetRecord& record)
{
	FileSetRecord rest = record;
	rest.files.clear();
	rest.removed.clear();
	for (const auto& e : record.files)
		if (stampOf(folder / record.committing_from / e.name) == e.stamp) rest.files.push_back(e);
	for (const auto& e : record.removed)
		if (stampOf(folder / e.name) == e.stamp) rest.removed.push_back(e);
	moveIntoPlace(folder, rest);
	FileSetRecord complete{record.kind, "", {}, {}};
	for (const auto& e : record.files)
		if (stampOf(folder / e.name) == e.stamp) complete.files.push_back(e);
	writeRecord(record_path, complete);
	return complete;
}

/// Why the file `name` (present) may not be replaced by a set of `kind`;
/// nullopt when the record proves esif wrote it.
std::optional<std::string> claimProblem(
	const fs::path& folder, const std::string& name, const std::string& kind, const std::optional<FileSetRecord>& record,
	const fs::path& record_path)
{
	const std::optional<FileStamp> stamp = stampOf(folder / name);
	if (!stamp) return "is not a regular file (a folder, link, device or FIFO is never replaced)";
	const std::string not_written = "is not a file esif wrote as " + kind + " (";
	if (!record) return not_written + "no record " + record_path.filename().string() + " beside it)";
	const RecordEntry* entry = record->file(name);
	if (!entry || record->kind != kind) return not_written + record_path.filename().string() + " does not list it)";
	if (!(entry->stamp == *stamp)) return "was changed after esif wrote it (its size or CRC differs from the record)";
	return std::nullopt;
}
}  // namespace

FileSet::FileSet(std::string kind, const std::vector<std::string>& files, const std::vector<NamedInput>& inputs)
	: kind_(std::move(kind))
{
	if (files.empty()) throw InputError("no output file given");
	for (const auto& f : files) requireOutputApart(f, inputs);
	folder_ = folderOf(fs::path(files.front()).lexically_normal());
	names_ = namesIn(folder_, files);
	first_ = folder_ / names_.front();
	ensureDirectory(folder_.string());
	lock_.emplace(first_, LockWait::No, "these files");
	const fs::path record_path = fileSetRecordOf(first_);
	std::optional<FileSetRecord> record = FileSetRecord::read(record_path);
	if (record && !record->committing_from.empty()) record = finishKilledCommit(folder_, record_path, *record);
	removeStalePartials(first_);
	removeStaleRecordCopies(record_path);
	for (const auto& name : names_)
		if (pathPresent((folder_ / name).string()))
			if (const auto problem = claimProblem(folder_, name, kind_, record, record_path))
				throw InputError(
					(folder_ / name).string() + ": exists and " + *problem + "; esif replaces only files it wrote: " +
					"not replaced (move it away, or choose another --out)");
	staging_ = partialFolderOf(first_);
	std::error_code ec;
	fs::create_directory(staging_, ec);
	if (ec) throw InputError(first_.string() + ": cannot create the folder " + staging_.string() + ": " + ec.message());
	termination::addPath(staging_.string());
}

FileSet::~FileSet()
{
	if (staging_.empty()) return;
	std::error_code ec;
	fs::remove_all(staging_, ec);
	termination::removePath(staging_.string());
}

std::string FileSet::staging(const std::string& file) const
{
	return (staging_ / fs::path(file).filename()).string();
}

void FileSet::commit()
{
	FileSetRecord record{kind_, staging_.filename().string(), {}, {}};
	std::error_code ec;
	for (fs::directory_iterator it(staging_, ec), end; !ec && it != end; it.increment(ec))
	{
		const std::string name = it->path().filename().string();
		const auto stamp = stampOf(it->path());
		if (!stamp || std::find(names_.begin(), names_.end(), name) == names_.end())
			throw InputError((folder_ / name).string() + ": written, but not one of the files of " + kind_);
		record.files.push_back({name, *stamp});
	}
	if (ec) throw InputError(staging_.string() + ": cannot list the written files: " + ec.message());
	// The previous set's files the new one does not have (the claim check
	// proved them esif's): a simulation's measurement-ID truth must not stay
	// beside a rawlog imported in its place.
	const fs::path record_path = fileSetRecordOf(first_);
	if (const auto previous = FileSetRecord::read(record_path))
		for (const auto& e : previous->files)
			if (!record.file(e.name) && std::find(names_.begin(), names_.end(), e.name) != names_.end())
				record.removed.push_back(e);
	syncFolder(staging_.string());
	{
		// No signal may end esif between the record and the last rename:
		// the record would promise files the cleanup then removes.
		const auto hold = termination::holdOff();
		writeRecord(record_path, record);
		moveIntoPlace(folder_, record);
		FileSetRecord complete = record;
		complete.committing_from.clear();
		complete.removed.clear();
		writeRecord(record_path, complete);
	}
	fs::remove_all(staging_, ec);
	termination::removePath(staging_.string());
	staging_.clear();
}

void FileSet::rethrowNamingTargets() const { rethrowWithPathReplaced(staging_.string(), folder_.string()); }

}  // namespace esif
