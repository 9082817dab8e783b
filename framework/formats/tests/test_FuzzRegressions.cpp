// Every input the fuzz targets found (a crash, a sanitizer report or memory
// beyond the limit in some earlier version) is kept in tests/fuzz/regressions
// and must now be read or refused in one line, in the ordinary build too.

#include <EsifTestSupport.h>
#include <G2oInput.h>
#include <GroundTruthInput.h>
#include <ImporterInput.h>
#include <LocalMapInput.h>

#include <esif/config/ConfigFile.h>
#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/formats/RawlogReader.h>
#include <esif/run/HostParams.h>

#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>

namespace
{
using namespace esif;

std::vector<std::string> keptInputs(const std::string& reader, const std::string& kind = "regressions")
{
	std::vector<std::string> out;
	const auto dir = std::filesystem::path(test::sourcePath("tests/fuzz/" + kind)) / reader;
	if (!std::filesystem::is_directory(dir)) return out;  // nothing found for this reader yet
	for (const auto& entry : std::filesystem::directory_iterator(dir)) out.push_back(entry.path().string());
	return out;
}
using Judge = fuzz::Verdict (*)(const std::string&);

/// Whether a reader has kept inputs yet (the importers' targets have found none).
enum class Kept
{
	Some,
	MaybeNone
};

/// The text readers' and importers' fuzz inputs (tests/fuzz/*Input.h):
/// every seed reads (so fuzzing starts from valid files), and every kept
/// input, each once accepted wrongly or allocating gigabytes, is refused in
/// one line.
void checkTextReader(const std::string& reader, Judge judge, Kept expected = Kept::Some)
{
	const auto seeds = keptInputs(reader, "seeds");
	ASSERT_FALSE(seeds.empty()) << reader;
	for (const auto& path : seeds)
	{
		const auto verdict = judge(test::readText(path));
		EXPECT_FALSE(verdict.refused) << path << " is a valid file";
		EXPECT_FALSE(verdict.finding) << path << ": " << verdict.finding.value_or("");
	}
	const auto kept = keptInputs(reader);
	if (expected == Kept::Some)
	{
		ASSERT_FALSE(kept.empty()) << reader;
	}
	for (const auto& path : kept)
	{
		const auto verdict = judge(test::readText(path));
		EXPECT_TRUE(verdict.refused) << path << " must be refused";
		EXPECT_FALSE(verdict.finding) << path << ": " << verdict.finding.value_or("");
	}
}
}  // namespace

TEST(FuzzRegressions, LocalMapSeedsReadAndKeptInputsAreRefusedInOneLine)
{
	checkTextReader("localmap", fuzz::localMapVerdict);
}

TEST(FuzzRegressions, G2oSeedsReadAndKeptInputsAreRefusedInOneLine) { checkTextReader("g2o", fuzz::g2oVerdict); }

TEST(FuzzRegressions, GroundTruthSeedsReadAndKeptInputsAreRefusedInOneLine)
{
	checkTextReader("ground_truth", fuzz::groundTruthVerdict);
}

/// The importers' seeds import, and every kept input (none found yet) is
/// refused in one line.
TEST(FuzzRegressions, ImporterSeedsImportAndKeptInputsAreRefusedInOneLine)
{
	checkTextReader("vicpark", fuzz::victoriaParkVerdict, Kept::MaybeNone);
	checkTextReader("mrclam", fuzz::mrclamVerdict, Kept::MaybeNone);
}

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
