#pragma once
/// \file CheckedWrite.h
/// Writes bytes to a file with every step checked (each write, fsync, close),
/// so a full disk or a quota is an error naming the file rather than a
/// truncated file reported as written. MRPT's gz streams and std::ofstream
/// leave some of those failures unreported; esif's outputs go through here.

#include <string>

namespace esif
{
/// Creates or truncates `path` and writes `bytes` to it, then fsyncs and
/// closes it. Throws InputError "`shown_name`: cannot write: <errno text>"
/// on any failure; `shown_name` is the name the user knows the file by (the
/// final name when `path` is a temporary one).
void writeBytesChecked(const std::string& path, const std::string& bytes, const std::string& shown_name);

/// fsyncs the folder `dir`, so the renames and creations in it survive a
/// crash. Throws InputError naming `dir` on failure.
void syncFolder(const std::string& dir);

}  // namespace esif
