// associations.txt: written from step reports, read back strictly (errors
// name file and line), and applied to a rawlog's measurement IDs only when
// it fits that rawlog step by step.

#include <EsifTestSupport.h>
#include <FakeRawlog.h>

#include <esif/core/Errors.h>
#include <esif/formats/AssociationFile.h>

#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>

namespace
{
using esif::Association;
using esif::StepReport;
using esif::test::makeRawlog;
using esif::test::TempDir;
using Kind = Association::Kind;

/// Three steps: {new 4, rejected}, nothing, {matched 4, new 9}.
std::vector<StepReport> threeSteps()
{
	return {
		StepReport{{{Kind::New, 4}, {Kind::Rejected, 12}}},
		StepReport{},
		StepReport{{{Kind::Matched, 4}, {Kind::New, 9}}},
	};
}

std::string write(const TempDir& dir, const std::string& text)
{
	const auto path = dir.file("associations.txt");
	std::ofstream(path) << text;
	return path;
}

std::string readError(const std::string& path)
{
	try
	{
		esif::readAssociationFile(path, 3);
	}
	catch (const esif::InputError& e)
	{
		return e.what();
	}
	return "";
}

const std::string kHeader = "# a comment\n# steps 3\n";

TEST(AssociationFile, TextHasCommentHeaderAndOneRowPerMeasurement)
{
	const std::string text = esif::associationFileText(threeSteps(), "EkfSlam", "x.rawlog");
	EXPECT_EQ(text.rfind("# esif associations.txt: data association of plugin EkfSlam on x.rawlog\n", 0), 0u) << text;
	EXPECT_NE(text.find("\n# steps 3\n"), std::string::npos) << text;
	// The rejected measurement is written with -1 whatever ID the report left in it.
	EXPECT_NE(text.find("\n0 0 new 4\n0 1 rejected -1\n2 0 matched 4\n2 1 new 9\n"), std::string::npos) << text;
}

TEST(AssociationFile, RoundTrip)
{
	TempDir dir;
	const auto path = dir.file("associations.txt");
	esif::writeAssociationFile(path, threeSteps(), "EkfSlam", "x.rawlog");
	const auto back = esif::readAssociationFile(path, 3);
	ASSERT_EQ(back.steps.size(), 3u);
	ASSERT_EQ(back.steps[0].associations.size(), 2u);
	EXPECT_EQ(back.steps[0].associations[0].kind, Kind::New);
	EXPECT_EQ(back.steps[0].associations[0].id, 4);
	EXPECT_EQ(back.steps[0].associations[1].kind, Kind::Rejected);
	EXPECT_EQ(back.steps[0].associations[1].id, -1);
	EXPECT_TRUE(back.steps[1].associations.empty());
	EXPECT_EQ(back.steps[2].associations[0].kind, Kind::Matched);
	EXPECT_EQ(back.steps[2].associations[1].id, 9);
}

TEST(AssociationFile, MissingFileIsNamed)
{
	TempDir dir;
	EXPECT_EQ(readError(dir.file("none.txt")), dir.file("none.txt") + ": association file not found");
	const auto path = write(dir, "0 0 new 1\n");
	EXPECT_EQ(readError(path), path + ":1: a row before the '# steps N' line");
	const auto no_header = write(dir, "# just a comment\n");
	EXPECT_EQ(readError(no_header), no_header + ": no '# steps N' line (not an esif associations.txt)");
}

TEST(AssociationFile, MalformedRowsNameFileAndLine)
{
	TempDir dir;
	const std::vector<std::pair<std::string, std::string>> cases = {
		{"0 0 new\n", ":3: expected 'step measurement kind landmark_id', found 3 values"},
		{"0 0 new 1 2\n", ":3: expected 'step measurement kind landmark_id', found 5 values"},
		{"0 x new 1\n", ":3: step, measurement and landmark_id must be whole numbers"},
		{"0 0 new 1.5\n", ":3: step, measurement and landmark_id must be whole numbers"},
		{"0 0 maybe 1\n", ":3: kind 'maybe' is not new, matched or rejected"},
		{"0 0 rejected 5\n", ":3: a rejected measurement has landmark_id -1, found 5"},
		{"3 0 new 1\n", ":3: step 3 beyond the 3 steps declared"},
		{"0 1 new 1\n", ":3: step 0 measurement 1 out of order (expected measurement 0)"},
		{"2 0 new 1\n0 0 new 2\n", ":4: step 0 after step 2: rows must be in step order"},
		{"0 0 new 1\n0 0 new 2\n", ":4: step 0 measurement 0 out of order (expected measurement 1)"},
		{"# steps 3\n", ":3: a second '# steps N' line"},
		{"# steps -1\n", ":3: expected '# steps N' with N a whole number"},
		{"0 0 new -5\n", ":3: landmark_id -5 is not a landmark ID in [0, 2147483647]"},
		{"0 0 matched 2147483648\n", ":3: landmark_id 2147483648 is not a landmark ID in [0, 2147483647]"},
	};
	for (const auto& [rows, expected] : cases)
	{
		const auto path = write(dir, kHeader + rows);
		const auto message = readError(path);
		EXPECT_EQ(message.rfind(path + expected, 0), 0u) << "rows: " << rows << "got: " << message;
	}
}

/// The declared step count is the rawlog's, checked before anything is
/// allocated: a 20-byte file declaring 10^8 (or 2^64 - 1) steps used to
/// allocate gigabytes (or end in an internal error).
TEST(AssociationFile, DeclaredStepsMustBeTheRawlogs)
{
	TempDir dir;
	for (const std::string n : {"100000000", "18446744073709551615", "4"})
	{
		const auto path = write(dir, "# steps " + n + "\n");
		EXPECT_EQ(readError(path), path + ":1: recorded for " + n + " steps, the rawlog has 3");
	}
	const auto overflow = write(dir, "# steps 18446744073709551616\n");
	EXPECT_EQ(readError(overflow), overflow + ":1: expected '# steps N' with N a whole number");
	std::filesystem::create_directory(dir.file("folder"));
	EXPECT_EQ(readError(dir.file("folder")), dir.file("folder") + ": association file is a folder, not a file");
}

TEST(AssociationFile, ApplySetsRecordedIdsAndKeepsTrueIds)
{
	// The rawlog has no IDs at step 0 and other IDs at step 2.
	auto log = makeRawlog({{{std::nullopt, std::nullopt}}, std::nullopt, {{40, 41}}});
	esif::RecordedAssociations recorded{threeSteps()};
	esif::applyAssociations(log, recorded, "a.txt");
	const auto& s0 = log.steps[0].scan->measurements;
	ASSERT_TRUE(s0[0].id.has_value());
	EXPECT_EQ(*s0[0].id, 4);
	EXPECT_FALSE(s0[1].id.has_value());	 // rejected: no ID, so it is not used
	const auto& s2 = log.steps[2].scan->measurements;
	EXPECT_EQ(s2[0].id.value_or(-7), 4);
	EXPECT_EQ(s2[1].id.value_or(-7), 9);
	EXPECT_TRUE(log.any_landmark_id);
	// Scoring still uses the rawlog's own IDs.
	EXPECT_FALSE(log.true_ids[0][0].has_value());
	EXPECT_EQ(log.true_ids[2][0].value_or(-7), 40);
	EXPECT_EQ(log.true_ids[2][1].value_or(-7), 41);
}

TEST(AssociationFile, ApplyRefusesAnotherRawlog)
{
	esif::RecordedAssociations recorded{threeSteps()};
	auto two_steps = makeRawlog({{{1, 2}}, std::nullopt});
	try
	{
		esif::applyAssociations(two_steps, recorded, "run/associations.txt");
		FAIL();
	}
	catch (const esif::InputError& e)
	{
		EXPECT_STREQ(e.what(), "run/associations.txt: recorded for 3 steps, the rawlog has 2");
	}
	// Step 2 has a measurement more than was recorded: nothing is changed.
	auto other = makeRawlog({{{1, 2}}, std::nullopt, {{3, 4, 5}}});
	try
	{
		esif::applyAssociations(other, recorded, "run/associations.txt");
		FAIL();
	}
	catch (const esif::InputError& e)
	{
		EXPECT_STREQ(e.what(), "run/associations.txt: step 2: 2 associations for 3 measurements");
	}
	EXPECT_EQ(other.steps[0].scan->measurements[0].id.value_or(-7), 1);
	// A step recorded without scan but with a scan in this rawlog.
	auto scan_at_1 = makeRawlog({{{1, 2}}, {{7}}, {{3, 4}}});
	EXPECT_THROW(esif::applyAssociations(scan_at_1, recorded, "a.txt"), esif::InputError);
}

}  // namespace
