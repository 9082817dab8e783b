#pragma once
/// \file GzipFileStream.h
/// An MRPT output stream that compresses what it is given with zlib and
/// writes it out as it goes (CheckedFileWriter): a gzip file of any size in
/// constant memory, with every write checked.

#include <esif/safeio/CheckedFileWriter.h>

#include <mrpt/io/CStream.h>

#include <string>
#include <vector>
#include <zlib.h>

namespace esif
{
class GzipFileStream : public mrpt::io::CStream
{
   public:
	/// Writes to `path`; errors name `shown_name`. `level`: zlib's 0-9.
	GzipFileStream(const std::string& path, const std::string& shown_name, int level);
	~GzipFileStream() override;

	size_t Write(const void* buffer, size_t count) override;
	/// Flushes zlib's last block and the gzip trailer, then fsyncs and closes.
	void finish();

	size_t Read(void*, size_t) override;
	uint64_t Seek(int64_t, mrpt::io::CStream::TSeekOrigin) override;
	uint64_t getTotalBytesCount() const override { return total_in_; }
	uint64_t getPosition() const override { return total_in_; }

   private:
	void deflateInput(int flush);

	CheckedFileWriter file_;
	z_stream z_{};
	bool open_ = false;
	std::vector<unsigned char> out_;
	uint64_t total_in_ = 0;
};

}  // namespace esif
