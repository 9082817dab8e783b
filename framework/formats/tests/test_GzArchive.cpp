/// \file test_GzArchive.cpp
/// Gzip files of MRPT objects written as they are serialized: the same
/// bytes as compressing the whole serialization at once, readable by MRPT's
/// own gz stream, at any size in constant memory.

#include <esif/formats/GzArchive.h>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/serialization/CArchive.h>

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;

namespace
{
std::string readBytes(const std::string& path)
{
	std::ifstream in(path, std::ios::binary);
	return std::string(std::istreambuf_iterator<char>(in), {});
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
	for (const int level : {1, 6, 9})
	{
		esif::writeGzArchiveAtomically(path, fill, level);
		EXPECT_EQ(readBytes(path), esif::gzipBytes(esif::serializedBytes(fill), level)) << "level " << level;
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
