/// \file test_FileSet.cpp
/// Output files among other files (FileSet.h): a file esif did not write,
/// or wrote as another kind of output, or that was changed since, is never
/// replaced; a set is committed whole or not at all; the previous set's
/// files the new one does not write go; a commit cut by a kill is refused
/// by readers and finished by the next writer.

#include <esif/core/Errors.h>
#include <esif/safeio/FileSet.h>

#include <EsifTestSupport.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace
{
using esif::FileSet;
using esif::InputError;
using esif::test::readText;
using esif::test::TempDir;

const char* const kKind = "a test set";

void put(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

/// Writes `texts` (one per file of `files`) as a set of kKind.
void writeSet(const std::vector<std::string>& files, const std::vector<std::string>& texts, const char* kind = kKind)
{
	esif::writeFileSet(kind, files, {}, [&](const FileSet& set) {
		for (std::size_t i = 0; i < texts.size(); ++i) put(set.staging(files[i]), texts[i]);
		return 0;
	});
}

/// The message of the InputError `action` throws ("" when none).
template <class Action>
std::string errorOf(Action&& action)
{
	try
	{
		action();
	}
	catch (const InputError& e)
	{
		return e.what();
	}
	return "";
}

TEST(FileSet, WritesNewFilesAndReplacesItsOwn)
{
	TempDir dir;
	const std::vector<std::string> files = {dir.file("a.log"), dir.file("a_truth.txt")};
	writeSet(files, {"one", "truth one"});
	EXPECT_EQ(readText(files[0]), "one");
	const std::string record = readText(dir.file(".a.log.esif-files"));
	EXPECT_NE(record.find("kind a test set\nstate complete\n"), std::string::npos) << record;
	EXPECT_NE(record.find(" a_truth.txt\n"), std::string::npos) << record;
	writeSet(files, {"two", "truth two"});
	EXPECT_EQ(readText(files[0]), "two");
	EXPECT_EQ(readText(files[1]), "truth two");
	// Nothing left beside them but the record.
	std::vector<std::string> left;
	for (const auto& e : fs::directory_iterator(dir.path())) left.push_back(e.path().filename().string());
	std::sort(left.begin(), left.end());
	EXPECT_EQ(left, (std::vector<std::string>{".a.log.esif-files", "a.log", "a_truth.txt"}));
}

TEST(FileSet, AFileEsifDidNotWriteIsNeverReplaced)
{
	TempDir dir;
	const std::vector<std::string> files = {dir.file("a.log"), dir.file("a_truth.txt")};
	put(files[1], "my notes");
	EXPECT_NE(errorOf([&] { writeSet(files, {"one", "truth"}); })
				  .find(files[1] + ": exists and is not a file esif wrote as a test set (no record .a.log.esif-files "
								   "beside it)"),
			  std::string::npos);
	EXPECT_EQ(readText(files[1]), "my notes");
	EXPECT_FALSE(fs::exists(files[0])) << "nothing written when one file is refused";
	fs::remove(files[1]);

	// Esif's, then changed by the user: theirs now.
	writeSet(files, {"one", "truth"});
	put(files[1], "truth, corrected by hand");
	EXPECT_NE(errorOf([&] { writeSet(files, {"two", "truth"}); }).find("was changed after esif wrote it"),
			  std::string::npos);
	EXPECT_EQ(readText(files[0]), "one");

	// Another kind of output of esif's at that name: not replaced either.
	const std::string other = dir.file("b.txt");
	writeSet({other}, {"a job list"}, "another kind");
	EXPECT_NE(errorOf([&] { writeSet({other}, {"x"}); })
				  .find("is not a file esif wrote as a test set (.b.txt.esif-files does not list it)"),
			  std::string::npos);
	EXPECT_EQ(readText(other), "a job list");

	// A folder, a link or a FIFO at an output's name.
	fs::create_directory(dir.file("c.log"));
	EXPECT_NE(errorOf([&] { writeSet({dir.file("c.log")}, {"x"}); }).find("is not a regular file"), std::string::npos);
	fs::create_symlink(files[0], dir.file("d.log"));
	EXPECT_NE(errorOf([&] { writeSet({dir.file("d.log")}, {"x"}); }).find("is not a regular file"), std::string::npos);
	EXPECT_EQ(readText(files[0]), "one");
}

TEST(FileSet, AFailedWriteLeavesThePreviousSetWhole)
{
	TempDir dir;
	const std::vector<std::string> files = {dir.file("a.log"), dir.file("a_truth.txt")};
	writeSet(files, {"one", "truth one"});
	EXPECT_THROW(esif::writeFileSet(kKind, files, {}, [&](const FileSet& set) {
		put(set.staging(files[0]), "two");
		throw InputError(set.staging(files[1]) + ": cannot write: No space left on device");
		return 0;
	}), InputError);
	EXPECT_EQ(readText(files[0]), "one");
	EXPECT_EQ(readText(files[1]), "truth one");
	// The error named the file where the user looks for it.
	EXPECT_EQ(errorOf([&] {
		esif::writeFileSet(kKind, files, {}, [&](const FileSet& set) -> int {
			throw InputError(set.staging(files[1]) + ": cannot write");
		});
	}), files[1] + ": cannot write");
}

TEST(FileSet, FilesThePreviousSetHadAndTheNewOneDoesNotAreRemoved)
{
	TempDir dir;
	const std::vector<std::string> files = {dir.file("a.log"), dir.file("a_truth.txt")};
	writeSet(files, {"simulated", "its truth"});
	writeSet(files, {"imported, without truth"});
	EXPECT_EQ(readText(files[0]), "imported, without truth");
	EXPECT_FALSE(fs::exists(files[1])) << "a truth that is not this file's own would be scored against";
}

TEST(FileSet, InputsAreNeverOutputs)
{
	TempDir dir;
	put(dir.file("in.txt"), "input");
	EXPECT_NE(errorOf([&] {
		esif::writeFileSet(kKind, {dir.file("in.txt")}, {{"the dataset", dir.file("in.txt")}},
						   [](const FileSet&) { return 0; });
	}).find("--out is the dataset"),
			  std::string::npos);
	EXPECT_EQ(readText(dir.file("in.txt")), "input");
}

/// A commit cut by SIGKILL between its renames, made by hand: the record
/// says "committing", the new first file is in place, the second still in
/// the partial folder, the old second file still there.
TEST(FileSet, ACommitCutByAKillIsRefusedByReadersAndFinishedByTheNextWriter)
{
	TempDir dir;
	const std::vector<std::string> files = {dir.file("a.log"), dir.file("a_truth.txt")};
	writeSet(files, {"old", "old truth"});
	// The new set, written whole elsewhere for its record's lines.
	fs::create_directory(dir.file("elsewhere"));
	writeSet({dir.file("elsewhere/a.log"), dir.file("elsewhere/a_truth.txt")}, {"new", "new truth"});
	std::string record = readText(dir.file("elsewhere/.a.log.esif-files"));
	const std::string partial = ".a.log.partial-999999";
	record.replace(record.find("state complete"), 14, "state committing " + partial);
	fs::create_directory(dir.file(partial));
	fs::rename(dir.file("elsewhere/a_truth.txt"), dir.file(partial + "/a_truth.txt"));
	fs::rename(dir.file("elsewhere/a.log"), files[0]);
	put(dir.file(".a.log.esif-files"), record);
	EXPECT_NE(errorOf([&] { esif::requireCompleteFileSet(files[0]); })
				  .find(files[0] + ": esif was stopped while replacing it and a_truth.txt"),
			  std::string::npos);
	// The next writer of the set finishes the commit, then replaces it as its own.
	writeSet(files, {"newest", "newest truth"});
	EXPECT_EQ(readText(files[0]), "newest");
	EXPECT_EQ(readText(files[1]), "newest truth");
	EXPECT_FALSE(fs::exists(dir.file(partial)));
	EXPECT_NO_THROW(esif::requireCompleteFileSet(files[0]));
}

}  // namespace
