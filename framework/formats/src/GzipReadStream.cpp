/// \file GzipReadStream.cpp
/// See GzipReadStream.h.

#include "GzipReadStream.h"

#include <esif/core/Errors.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace esif
{
GzipReadStream::GzipReadStream(const std::string& path) : path_(path)
{
	file_ = ::gzopen(path.c_str(), "rb");
	if (!file_) throw InputError(path + ": cannot open: " + std::strerror(errno));
}

GzipReadStream::~GzipReadStream()
{
	if (file_) ::gzclose(file_);
}

size_t GzipReadStream::Read(void* buffer, size_t count)
{
	// gzread takes an unsigned count; large values are read in pieces.
	constexpr size_t kPiece = size_t{1} << 30;
	size_t done = 0;
	while (done < count)
	{
		const int n = ::gzread(file_, static_cast<char*>(buffer) + done, static_cast<unsigned>(std::min(count - done, kPiece)));
		if (n < 0)
		{
			int code = 0;
			throw InputError(path_ + ": corrupt compressed data: " + ::gzerror(file_, &code));
		}
		if (n == 0) break;
		done += static_cast<size_t>(n);
	}
	if (done < count) return 0;	 // the data ends inside this value: none of it (WholeReadStream.h)
	position_ += done;
	return done;
}

size_t GzipReadStream::Write(const void*, size_t) { throw std::logic_error("GzipReadStream is read-only"); }

uint64_t GzipReadStream::Seek(int64_t, mrpt::io::CStream::TSeekOrigin)
{
	throw std::logic_error("GzipReadStream reads forward only");
}

}  // namespace esif
