#pragma once
/// \file AtomicFile.h
/// Every output is written under a temporary name in its final folder and
/// renamed into place, so a reader never sees a half-written file.

#include <functional>
#include <string>

namespace esif
{
/// Calls `write(tmp_path)` to produce the file, then renames tmp_path to
/// `path`. On any exception the temporary file is removed and the exception
/// is rethrown (as InputError naming `path` when it is not already an esif error).
/// The temporary file is also removed if a signal ends the process
/// (TerminationCleanup.h). `write` must check its own writes: prefer
/// writeBytesAtomically, or GzArchive.h for MRPT objects.
void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write);

/// Writes `bytes` to `path` atomically with every step checked
/// (CheckedWrite.h): a full disk is an InputError naming `path`.
void writeBytesAtomically(const std::string& path, const std::string& bytes);

/// Writes `text` to `path` atomically and checked (writeBytesAtomically).
void writeTextAtomically(const std::string& path, const std::string& text);

/// Creates `dir` and its parents; throws InputError naming it on failure.
void ensureDirectory(const std::string& dir);

}  // namespace esif
