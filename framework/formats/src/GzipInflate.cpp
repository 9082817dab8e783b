#include "GzipInflate.h"

#include <esif/core/Errors.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <memory>
#include <unistd.h>
#include <zlib.h>

namespace esif
{
namespace
{
struct GzCloser
{
	void operator()(gzFile_s* f) const { gzclose(f); }
};
using GzHandle = std::unique_ptr<gzFile_s, GzCloser>;

/// zlib's own words for a failed read, e.g. "incorrect data check".
std::string gzErrorText(gzFile f)
{
	int code = Z_OK;
	const char* text = gzerror(f, &code);
	if (code == Z_ERRNO) return std::strerror(errno);
	return text && *text ? text : "unknown zlib error";
}
/// A gzip bomb (a few kilobytes inflating to gigabytes) must not take the
/// machine: the inflated bytes may fill at most a quarter of physical memory.
std::size_t inflatedSizeCap()
{
	const long pages = sysconf(_SC_PHYS_PAGES), page_size = sysconf(_SC_PAGESIZE);
	if (pages <= 0 || page_size <= 0) return std::size_t{1} << 32;
	return static_cast<std::size_t>(pages) * static_cast<std::size_t>(page_size) / 4;
}
}  // namespace

InflatedFile inflateFile(const std::string& path)
{
	std::error_code ec;
	const auto size = std::filesystem::file_size(path, ec);
	if (ec) throw InputError(path + ": cannot read: " + ec.message());
	if (size == 0) throw InputError(path + ": file is empty");
	GzHandle file(gzopen(path.c_str(), "rb"));
	if (!file) throw InputError(path + ": cannot open: " + std::strerror(errno));
	gzbuffer(file.get(), 1 << 17);

	InflatedFile out;
	constexpr unsigned kChunk = 1 << 20;
	const std::size_t cap = inflatedSizeCap();
	for (;;)
	{
		const std::size_t at = out.bytes.size();
		if (at > cap)
			throw InputError(path + ": inflates to over " + std::to_string(cap >> 20) +
							 " MiB, a quarter of this machine's memory (reading a rawlog takes several times its "
							 "inflated size)");
		out.bytes.resize(at + kChunk);
		const int n = gzread(file.get(), out.bytes.data() + at, kChunk);
		if (n < 0)
			throw InputError(path + ": gzip data is corrupt after " + std::to_string(at) +
							 " inflated bytes (zlib: " + gzErrorText(file.get()) + ")");
		out.bytes.resize(at + static_cast<std::size_t>(n));
		if (n == 0) break;
	}
	int code = Z_OK;
	gzerror(file.get(), &code);
	// Z_BUF_ERROR: "the input file ended in the middle of a gzip stream" (zlib.h).
	out.stream_truncated = code == Z_BUF_ERROR;
	if (out.bytes.empty())
		throw InputError(path + (out.stream_truncated ? ": gzip stream is cut before its first byte of data"
													  : ": file holds no data"));
	out.bytes.shrink_to_fit();
	return out;
}

}  // namespace esif
