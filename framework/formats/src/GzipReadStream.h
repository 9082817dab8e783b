#pragma once
/// \file GzipReadStream.h
/// An MRPT input stream over a file, inflated as it is read when it is
/// gzip-compressed (zlib's gzread passes a plain file through): a second
/// pass over a rawlog in constant memory (RawlogFrames.cpp). Like
/// WholeReadStream, a read hands out every byte asked for or none, so MRPT
/// never keeps a value read in part.

#include <mrpt/io/CStream.h>

#include <cstdint>
#include <string>
#include <zlib.h>

namespace esif
{
class GzipReadStream : public mrpt::io::CStream
{
   public:
	/// Throws InputError naming `path` when it cannot be opened.
	explicit GzipReadStream(const std::string& path);
	~GzipReadStream() override;
	GzipReadStream(const GzipReadStream&) = delete;
	GzipReadStream& operator=(const GzipReadStream&) = delete;

	/// Throws InputError naming the file on corrupt gzip data.
	size_t Read(void* buffer, size_t count) override;
	size_t Write(const void*, size_t) override;
	uint64_t Seek(int64_t, mrpt::io::CStream::TSeekOrigin) override;
	uint64_t getTotalBytesCount() const override { return position_; }
	uint64_t getPosition() const override { return position_; }

   private:
	std::string path_;
	gzFile file_ = nullptr;
	uint64_t position_ = 0;
};

}  // namespace esif
