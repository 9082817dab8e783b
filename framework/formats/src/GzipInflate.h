#pragma once
/// \file GzipInflate.h
/// Reads a whole file into memory, inflating it when it is gzip-compressed
/// (MRPT rawlogs usually are; plain files pass through). zlib checks the
/// stream here, before MRPT sees a byte: a CRC mismatch is an error, not
/// MRPT's warning, and a cut stream is reported as such.

#include <string>

namespace esif
{
struct InflatedFile
{
	std::string bytes;
	/// The gzip stream ended before its trailer (a recording that was cut):
	/// `bytes` holds everything up to the cut.
	bool stream_truncated = false;
};

/// Throws InputError naming `path` when it cannot be opened or read, is
/// empty, inflates to more than a quarter of physical memory, or its gzip
/// data fails zlib's checks (CRC, corrupt deflate data).
InflatedFile inflateFile(const std::string& path);

}  // namespace esif
