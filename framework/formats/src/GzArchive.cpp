/// \file GzArchive.cpp
/// In-memory serialization and gzip; see GzArchive.h.

#include <esif/core/Errors.h>
#include <esif/formats/GzArchive.h>
#include <esif/safeio/AtomicFile.h>

#include <mrpt/io/CMemoryStream.h>

#include <zlib.h>

namespace esif
{
namespace
{
/// deflateInit2's windowBits: 15 (32 KiB window) + 16 asks for a gzip
/// header and trailer instead of zlib's, which is what gzopen() reads.
constexpr int kGzipWindowBits = 15 + 16;
constexpr int kMemLevel = 8;  // zlib's default
constexpr std::size_t kChunk = 1 << 16;
}  // namespace

std::string gzipBytes(const std::string& raw, int level)
{
	z_stream z{};
	if (deflateInit2(&z, level, Z_DEFLATED, kGzipWindowBits, kMemLevel, Z_DEFAULT_STRATEGY) != Z_OK)
		throw InputError("gzip: cannot initialise zlib");
	z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data()));
	z.avail_in = static_cast<uInt>(raw.size());
	// One call with Z_FINISH is fine for inputs below 4 GiB (avail_in is a uInt).
	if (raw.size() != z.avail_in)
	{
		deflateEnd(&z);
		throw InputError("gzip: input of " + std::to_string(raw.size()) + " bytes is too large");
	}
	std::string out;
	int rc = Z_OK;
	while (rc != Z_STREAM_END)
	{
		const std::size_t before = out.size();
		out.resize(before + kChunk);
		z.next_out = reinterpret_cast<Bytef*>(&out[before]);
		z.avail_out = static_cast<uInt>(kChunk);
		rc = deflate(&z, Z_FINISH);
		out.resize(before + kChunk - z.avail_out);
		if (rc != Z_OK && rc != Z_STREAM_END && rc != Z_BUF_ERROR)
		{
			deflateEnd(&z);
			throw InputError("gzip: deflate failed (zlib code " + std::to_string(rc) + ")");
		}
	}
	deflateEnd(&z);
	return out;
}

std::string serializedBytes(const std::function<void(mrpt::serialization::CArchive&)>& fill)
{
	mrpt::io::CMemoryStream memory;
	auto archive = mrpt::serialization::archiveFrom(memory);
	fill(archive);
	return std::string(static_cast<const char*>(memory.getRawBufferData()), memory.getTotalBytesCount());
}

void writeGzArchiveAtomically(
	const std::string& path, const std::function<void(mrpt::serialization::CArchive&)>& fill, int level)
{
	writeBytesAtomically(path, gzipBytes(serializedBytes(fill), level));
}

}  // namespace esif
