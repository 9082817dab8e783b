// landmark_identities.txt: written from a final map's identities, read back
// strictly (errors name file and line), and read with a run folder only
// when it lists exactly the landmarks of landmarks.txt.

#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/formats/LandmarkIdentityFile.h>
#include <esif/formats/RunOutputReader.h>

#include <gtest/gtest.h>
#include <fstream>

namespace
{
using esif::LandmarkIdentities;
using esif::test::TempDir;

/// Landmark 7 stands for true landmark 3 (5 of its 6 measurements), 8 for
/// true landmark 3 as well (a duplicate), 9 for none (clutter).
LandmarkIdentities threeLandmarks()
{
	return {true, {{7, 3, 5, 6}, {8, 3, 2, 2}, {9, std::nullopt, 0, 4}}};
}

std::string write(const TempDir& dir, const std::string& name, const std::string& text)
{
	const auto path = dir.file(name);
	std::ofstream(path) << text;
	return path;
}

template <class F>
std::string inputErrorOf(F f)
{
	try
	{
		f();
	}
	catch (const esif::InputError& e)
	{
		return e.what();
	}
	return "";
}

std::string readError(const std::string& path)
{
	return inputErrorOf([&] { esif::readLandmarkIdentityFile(path); });
}

TEST(LandmarkIdentityFile, TextHasHeaderAndOneRowPerLandmark)
{
	const std::string text = esif::landmarkIdentityFileText(threeLandmarks());
	EXPECT_EQ(text.rfind("# esif landmark_identities.txt:", 0), 0u) << text;
	EXPECT_NE(text.find("\n# truth yes\n7 3 5 6\n8 3 2 2\n9 -1 0 4\n"), std::string::npos) << text;
	EXPECT_NE(esif::landmarkIdentityFileText({false, {{4, std::nullopt, 0, 2}}}).find("\n# truth no\n4 -1 0 2\n"),
			  std::string::npos);
}

TEST(LandmarkIdentityFile, RoundTrip)
{
	TempDir dir;
	const auto path = dir.file("ids.txt");
	esif::writeLandmarkIdentityFile(path, threeLandmarks());
	const LandmarkIdentities back = esif::readLandmarkIdentityFile(path);
	EXPECT_TRUE(back.truth);
	ASSERT_EQ(back.landmarks.size(), 3u);
	EXPECT_EQ(back.landmarks[0].landmark, 7);
	EXPECT_EQ(back.landmarks[0].true_id, 3);
	EXPECT_EQ(back.landmarks[0].votes, 5u);
	EXPECT_EQ(back.landmarks[0].measurements, 6u);
	EXPECT_FALSE(back.landmarks[2].true_id);
	EXPECT_EQ(back.landmarks[2].measurements, 4u);
}

TEST(LandmarkIdentityFile, MissingOrHeaderlessFileIsNamed)
{
	TempDir dir;
	EXPECT_EQ(readError(dir.file("none.txt")), dir.file("none.txt") + ": landmark identity file not found");
	const auto row_first = write(dir, "a.txt", "1 2 1 1\n");
	EXPECT_EQ(readError(row_first), row_first + ":1: a row before the '# truth yes|no' line");
	const auto no_header = write(dir, "b.txt", "# a comment\n");
	EXPECT_EQ(readError(no_header), no_header + ": no '# truth yes|no' line (not an esif landmark_identities.txt)");
}

TEST(LandmarkIdentityFile, MalformedRowsNameFileAndLine)
{
	TempDir dir;
	const std::vector<std::pair<std::string, std::string>> cases = {
		{"# truth yes\n1 2 1\n", ":2: expected 'landmark_id true_id votes measurements', found 3 values"},
		{"# truth yes\n1 2 1 x\n", ":2: every value must be a whole number"},
		{"# truth yes\n1 2 -1 1\n", ":2: every value must be a whole number"},
		{"# truth maybe\n", ":1: expected '# truth yes' or '# truth no'"},
		{"# truth yes\n# truth no\n", ":2: a second '# truth' line"},
		{"# truth yes\n-3 2 1 1\n", ":2: landmark_id -3 is not a landmark ID in [0, 2147483647]"},
		{"# truth yes\n1 2147483648 1 1\n", ":2: true_id 2147483648 is not a landmark ID in [0, 2147483647] nor -1"},
		{"# truth yes\n1 2 3 2\n", ":2: more votes (3) than measurements (2)"},
		{"# truth yes\n1 -1 1 2\n", ":2: true_id -1 goes with 0 votes and a true landmark with at least one"},
		{"# truth yes\n1 4 0 2\n", ":2: true_id -1 goes with 0 votes and a true landmark with at least one"},
		{"# truth no\n1 4 1 2\n", ":2: a true landmark under '# truth no'"},
		{"# truth yes\n1 4 1 2\n\n1 5 1 1\n", ":4: landmark 1 listed twice (first on line 2)"},
	};
	for (const auto& [text, expected] : cases)
	{
		const auto path = write(dir, "bad.txt", text);
		const auto message = readError(path);
		EXPECT_EQ(message.rfind(path + expected, 0), 0u) << text << "got: " << message;
	}
}

/// A run folder's identities must cover landmarks.txt, neither more nor less.
TEST(LandmarkIdentityFile, RunFolderIdentitiesMustListItsLandmarks)
{
	TempDir dir;
	write(dir, "trajectory.tum", "0 0 0 0 0 0 0 1\n");
	write(dir, "landmarks.txt", "7 1 2 1 0 1\n9 3 4 1 0 1\n");
	EXPECT_FALSE(esif::readRunOutputs(dir.path()).identities) << "optional: another solver's folder has none";
	const auto path = write(dir, "landmark_identities.txt", "# truth yes\n7 3 5 6\n9 -1 0 4\n");
	const auto run = esif::readRunOutputs(dir.path());
	ASSERT_TRUE(run.identities);
	EXPECT_EQ(run.identities->landmarks.size(), 2u);
	write(dir, "landmark_identities.txt", "# truth yes\n7 3 5 6\n");
	EXPECT_EQ(inputErrorOf([&] { esif::readRunOutputs(dir.path()); }),
			  path + ": no row for landmark 9 of landmarks.txt");
	write(dir, "landmark_identities.txt", "# truth yes\n7 3 5 6\n9 -1 0 4\n11 -1 0 1\n");
	EXPECT_EQ(inputErrorOf([&] { esif::readRunOutputs(dir.path()); }), path + ": landmark 11 is not in landmarks.txt");
}

}  // namespace
