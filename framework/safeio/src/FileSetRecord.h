#pragma once
/// \file FileSetRecord.h
/// The record a file set keeps beside its files (FileSet.h): what kind of
/// output the set is, whether it is complete or being committed, and every
/// file it put there with its size and CRC-32.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// What a file held when esif wrote it.
struct FileStamp
{
	std::uintmax_t size = 0;
	std::uint32_t crc = 0;	///< CRC-32 (zlib) of its bytes
	bool operator==(const FileStamp& o) const { return size == o.size && crc == o.crc; }
	bool operator!=(const FileStamp& o) const { return !(*this == o); }
};

/// The stamp of the regular file at `path` (a symbolic link is not
/// followed: it is no file esif wrote); nullopt when nothing is there or it
/// is not a regular file. Reads the file (a FIFO is never opened for it).
std::optional<FileStamp> stampOf(const std::filesystem::path& path);

struct RecordEntry
{
	std::string name;  ///< a file name in the record's folder
	FileStamp stamp;
};

struct FileSetRecord
{
	std::string kind;
	/// While committing: the partial folder (a name in the record's folder)
	/// the files are renamed from; empty once complete.
	std::string committing_from;
	std::vector<RecordEntry> files;	 ///< what the set is (or, while committing, will be)
	std::vector<RecordEntry> removed;  ///< while committing: files of the previous set to remove

	/// The entry of `name` in `files`, or null.
	const RecordEntry* file(const std::string& name) const;

	std::string text() const;
	/// The record at `path`; nullopt when there is none. InputError naming
	/// "file:line" when it is malformed.
	static std::optional<FileSetRecord> read(const std::filesystem::path& path);
};

/// Whether `name` can be a file of a set: a plain file name (no '/', not
/// "." or ".."), without a control character (a record line holds it).
bool isRecordableName(const std::string& name);

}  // namespace esif
