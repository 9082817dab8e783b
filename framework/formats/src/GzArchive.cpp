/// \file GzArchive.cpp
/// Streamed serialization and gzip; see GzArchive.h.

#include <esif/core/Errors.h>
#include <esif/formats/GzArchive.h>
#include <esif/safeio/AtomicFile.h>
#include "GzipFileStream.h"

#include <algorithm>
#include <stdexcept>
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

GzipFileStream::GzipFileStream(const std::string& path, const std::string& shown_name, int level)
	: file_(path, shown_name), out_(kChunk)
{
	if (deflateInit2(&z_, level, Z_DEFLATED, kGzipWindowBits, kMemLevel, Z_DEFAULT_STRATEGY) != Z_OK)
		throw InputError(file_.shownName() + ": gzip: cannot initialise zlib");
	open_ = true;
}

GzipFileStream::~GzipFileStream()
{
	if (open_) deflateEnd(&z_);
}

size_t GzipFileStream::Write(const void* buffer, size_t count)
{
	// deflate takes at most 4 GiB at a time (avail_in is a uInt).
	const auto* bytes = static_cast<const unsigned char*>(buffer);
	while (count > 0)
	{
		const std::size_t piece = std::min<std::size_t>(count, kChunk);
		z_.next_in = const_cast<Bytef*>(bytes);
		z_.avail_in = static_cast<uInt>(piece);
		deflateInput(Z_NO_FLUSH);
		bytes += piece;
		count -= piece;
		total_in_ += piece;
	}
	return static_cast<size_t>(bytes - static_cast<const unsigned char*>(buffer));
}

void GzipFileStream::deflateInput(int flush)
{
	int rc = Z_OK;
	do
	{
		z_.next_out = out_.data();
		z_.avail_out = static_cast<uInt>(out_.size());
		rc = deflate(&z_, flush);
		if (rc != Z_OK && rc != Z_STREAM_END && rc != Z_BUF_ERROR)
			throw InputError(file_.shownName() + ": gzip: deflate failed (zlib code " + std::to_string(rc) + ")");
		file_.write(out_.data(), out_.size() - z_.avail_out);
	} while (z_.avail_out == 0 || (flush == Z_FINISH && rc != Z_STREAM_END));
}

void GzipFileStream::finish()
{
	z_.next_in = nullptr;
	z_.avail_in = 0;
	deflateInput(Z_FINISH);
	deflateEnd(&z_);
	open_ = false;
	file_.finish();
}

size_t GzipFileStream::Read(void*, size_t) { throw std::logic_error("GzipFileStream is write-only"); }

uint64_t GzipFileStream::Seek(int64_t, mrpt::io::CStream::TSeekOrigin)
{
	throw std::logic_error("GzipFileStream cannot seek");
}

void writeGzArchiveAtomically(
	const std::string& path, const std::function<void(mrpt::serialization::CArchive&)>& fill, int level)
{
	// Streamed: the serialized bytes are compressed and written as they
	// come, so a rawlog of millions of steps needs no more memory than one.
	writeAtomically(path, [&](const std::string& tmp) {
		GzipFileStream out(tmp, path, level);
		auto archive = mrpt::serialization::archiveFrom(out);
		fill(archive);
		out.finish();
	});
}

}  // namespace esif
