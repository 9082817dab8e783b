// Every input the fuzz targets found (a crash, a sanitizer report or memory
// beyond the limit in some earlier version) is kept in tests/fuzz/regressions
// and must now be read or refused in one line, in the ordinary build too.

#include <EsifTestSupport.h>

#include <esif/config/ConfigFile.h>
#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/io/RawlogReader.h>
#include <esif/run/HostParams.h>

#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>

namespace
{
using namespace esif;

std::vector<std::string> keptInputs(const std::string& reader)
{
	std::vector<std::string> out;
	const auto dir = std::filesystem::path(test::sourcePath("tests/fuzz/regressions")) / reader;
	if (!std::filesystem::is_directory(dir)) return out;  // nothing found for this reader yet
	for (const auto& entry : std::filesystem::directory_iterator(dir)) out.push_back(entry.path().string());
	return out;
}
}  // namespace

TEST(FuzzRegressions, RawlogInputsAreReadOrRefusedInOneLine)
{
	const auto inputs = keptInputs("rawlog");
	ASSERT_FALSE(inputs.empty());
	for (const auto& path : inputs)
	{
		try
		{
			readRawlogFromMemory("kept.rawlog", test::readText(path));
		}
		catch (const InputError& e)
		{
			const std::string line = e.what();
			EXPECT_EQ(line.find('\n'), std::string::npos) << path << ": " << line;
			EXPECT_EQ(line.rfind("kept.rawlog", 0), 0u) << path << ": " << line;
		}
	}
}

TEST(FuzzRegressions, IniInputsLoadOrAreRefusedInOneLine)
{
	for (const auto& path : keptInputs("ini"))
	{
		try
		{
			const auto cfg = ConfigFile::fromText(test::readText(path), "kept.ini");
			HostParams host;
			loadParams(host, cfg.section("esif"));
		}
		catch (const ConfigError& e)
		{
			EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << path << ": " << e.what();
		}
	}
}
