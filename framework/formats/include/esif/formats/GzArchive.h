#pragma once
/// \file GzArchive.h
/// MRPT serialization written as a gzip file without MRPT's gz streams:
/// objects are serialized, compressed with zlib and written as they come
/// through the checked writer (CheckedFileWriter.h), in constant memory. CFileGZOutputStream
/// reports success on a full disk, so a truncated map would otherwise be
/// renamed into place. The files are ordinary gzip, as MRPT writes them, so
/// CFileGZInputStream, loadFromFile() and MRPT's tools read them unchanged.

#include <mrpt/serialization/CArchive.h>

#include <functional>
#include <string>

namespace esif
{
/// Writes what `fill` serializes to `path` as gzip, atomically
/// (AtomicFile.h) and checked: an error names `path`. For map files and for
/// gz rawlogs (the simulator and importers can adopt it in place of a
/// CFileGZOutputStream inside writeAtomically).
void writeGzArchiveAtomically(
	const std::string& path, const std::function<void(mrpt::serialization::CArchive&)>& fill, int level = 6);

}  // namespace esif
