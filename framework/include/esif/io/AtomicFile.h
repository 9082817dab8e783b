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
void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write);

/// Writes `text` to `path` atomically.
void writeTextAtomically(const std::string& path, const std::string& text);

/// Creates `dir` and its parents; throws InputError naming it on failure.
void ensureDirectory(const std::string& dir);

}  // namespace esif
