/// \file test_GzArchive.cpp
/// Gzip files of MRPT objects written as they are serialized: the same
/// bytes as compressing the whole serialization at once, readable by MRPT's
/// own gz stream, at any size in constant memory.

#include <esif/formats/GzArchive.h>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/serialization/CArchive.h>

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <string>
#include <unistd.h>
#include <zlib.h>

namespace fs = std::filesystem;

namespace
{
std::string readBytes(const std::string& path)
{
	std::ifstream in(path, std::ios::binary);
	return std::string(std::istreambuf_iterator<char>(in), {});
}

/// `raw` compressed in one call, as one gzip member (windowBits 15 + 16,
/// memLevel 8: what the writer uses).
std::string gzipAtOnce(const std::string& raw, int level)
{
	z_stream z{};
	deflateInit2(&z, level, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
	std::string out(deflateBound(&z, raw.size()), '\0');
	z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data()));
	z.avail_in = static_cast<uInt>(raw.size());
	z.next_out = reinterpret_cast<Bytef*>(out.data());
	z.avail_out = static_cast<uInt>(out.size());
	EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
	out.resize(out.size() - z.avail_out);
	deflateEnd(&z);
	return out;
}

/// The file inflated by zlib's own gzip reader.
std::string inflated(const std::string& path)
{
	gzFile in = gzopen(path.c_str(), "rb");
	std::string out;
	char buffer[1 << 16];
	for (int n; (n = gzread(in, buffer, sizeof(buffer))) > 0;) out.append(buffer, static_cast<std::size_t>(n));
	gzclose(in);
	return out;
}

/// Many poses and a block of bytes that do not compress: several of the
/// stream's 64 KiB output chunks.
void fill(mrpt::serialization::CArchive& ar)
{
	for (int i = 0; i < 20000; ++i) ar << mrpt::poses::CPose2D(i * 0.1, -i * 0.2, i * 1e-3);
	std::string noise(300000, '\0');
	unsigned state = 12345;
	for (auto& c : noise) c = static_cast<char>((state = state * 1103515245u + 12345u) >> 24);
	ar << noise;
}
}  // namespace

TEST(GzArchive, StreamedFileIsTheWholeStreamCompressedAndMrptReadsIt)
{
	const fs::path dir = fs::temp_directory_path() / ("esif_gz_" + std::to_string(::getpid()));
	fs::create_directories(dir);
	const std::string path = (dir / "poses.gz").string();
	mrpt::io::CMemoryStream memory;
	auto memory_archive = mrpt::serialization::archiveFrom(memory);
	fill(memory_archive);
	const std::string serialized(static_cast<const char*>(memory.getRawBufferData()), memory.getTotalBytesCount());
	for (const int level : {1, 6, 9})
	{
		esif::writeGzArchiveAtomically(path, fill, level);
		EXPECT_EQ(readBytes(path), gzipAtOnce(serialized, level)) << "level " << level;
		EXPECT_EQ(inflated(path), serialized) << "level " << level;
	}
	mrpt::io::CFileGZInputStream in(path);
	auto ar = mrpt::serialization::archiveFrom(in);
	mrpt::poses::CPose2D p;
	for (int i = 0; i < 20000; ++i) ar >> p;
	EXPECT_DOUBLE_EQ(p.x(), 19999 * 0.1);
	std::string noise;
	ar >> noise;
	EXPECT_EQ(noise.size(), 300000u);
	fs::remove_all(dir);
}
