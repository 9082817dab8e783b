// Output folders are all-or-nothing (RunFolder.h): a full disk, a signal, a
// concurrent writer, a user's folder or a read-only parent leave --out as it
// was (or absent), with one error line naming the real cause, and no
// partial folder, lock or temporary file beside it.

#include <ChildProcess.h>
#include <EsifTestSupport.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sys/file.h>
#include <sys/prctl.h>
#include <thread>

namespace fs = std::filesystem;

namespace
{
using esif::test::finish;
using esif::test::readText;
using esif::test::runEsif;
using esif::test::sourcePath;
using esif::test::spawnEsif;
using esif::test::TempDir;

const std::string kRawlog = sourcePath("rawlogs/grid196.rawlog");

std::vector<std::string> runArgs(const std::string& config, const std::string& rawlog, const std::string& out)
{
	return {"run", "-q", "--config", sourcePath("configs/" + config), "--rawlog", rawlog, "--out", out};
}

std::pair<int, std::string> runToEnd(const std::vector<std::string>& args) { return finish(spawnEsif(args)); }

/// The lines of `text` that report an error.
std::vector<std::string> errorLines(const std::string& text)
{
	std::vector<std::string> lines;
	std::istringstream in(text);
	for (std::string line; std::getline(in, line);)
		if (line.rfind("esif: error: ", 0) == 0) lines.push_back(line);
	return lines;
}

/// What a writer may leave beside or inside its folder if it does not
/// clean up: partial folders, lock files, temporary files.
std::vector<std::string> leftovers(const std::string& dir)
{
	std::vector<std::string> found;
	for (const auto& e : fs::recursive_directory_iterator(dir))
	{
		const std::string name = e.path().filename().string();
		if (name.find(".partial-") != std::string::npos || e.path().extension() == ".lock" ||
			e.path().extension() == ".tmp")
			found.push_back(e.path().string());
	}
	return found;
}

/// Waits (up to 60 s) until a partial folder whose name starts with
/// `prefix` exists in `dir`; returns its path ("" on time-out).
std::string waitForPartial(const std::string& dir, const std::string& prefix)
{
	for (int i = 0; i < 6000; ++i)
	{
		std::error_code ec;
		for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
			if (it->path().filename().string().rfind(prefix, 0) == 0) return it->path().string();
		std::this_thread::sleep_for(std::chrono::milliseconds(10));
	}
	return "";
}

/// A rawlog long enough that a run of it is still going when the test
/// signals it: 1225 features, the EKF's cost grows with the map squared.
std::string longRawlog(const TempDir& dir)
{
	const std::string rawlog = dir.file("long.rawlog");
	const auto r = runEsif("simulate --config '" + sourcePath("configs/sim/grid1225.ini") + "' --out '" + rawlog + "'");
	EXPECT_EQ(r.exit_code, 0) << r.out;
	return rawlog;
}

TEST(RunFolder, FullDiskIsOneErrorLineNamingTheFileAndLeavesNoFolder)
{
	TempDir dir;
	const std::string out = dir.file("out");
	// 64 KiB: below map.simplemap and map.png of grid196, above the config.
	const auto [code, text] = finish(spawnEsif(runArgs("ekf.ini", kRawlog, out), 64 * 1024));
	EXPECT_EQ(code, 1) << text;
	const auto errors = errorLines(text);
	ASSERT_EQ(errors.size(), 1u) << text;
	EXPECT_NE(errors[0].find("esif: error: " + out + "/"), std::string::npos) << "names the file in --out: " << text;
	EXPECT_NE(errors[0].find(std::strerror(EFBIG)), std::string::npos) << text;
	EXPECT_FALSE(fs::exists(out));
	EXPECT_TRUE(leftovers(dir.path()).empty());
}

// The simulator's and importer's gz rawlogs go through the same checked
// writer: a full disk is one line naming the rawlog, and no file is left.
TEST(RunFolder, FullDiskWhileSimulatingLeavesNoRawlog)
{
	TempDir dir;
	const std::string rawlog = dir.file("sim.rawlog");
	// 16 KiB: below the gzipped rawlog of configs/sim/small.ini (200 steps).
	const auto [code, text] = finish(spawnEsif(
		{"simulate", "--config", sourcePath("configs/sim/small.ini"), "--out", rawlog}, 16 * 1024));
	EXPECT_EQ(code, 1) << text;
	const auto errors = errorLines(text);
	ASSERT_EQ(errors.size(), 1u) << text;
	EXPECT_NE(errors[0].find(rawlog), std::string::npos) << text;
	EXPECT_NE(errors[0].find(std::strerror(EFBIG)), std::string::npos) << text;
	EXPECT_FALSE(fs::exists(rawlog));
	EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(RunFolder, FullDiskOnAReRunKeepsThePreviousFolder)
{
	TempDir dir;
	const std::string out = dir.file("out");
	ASSERT_EQ(runToEnd(runArgs("ekf.ini", kRawlog, out)).first, 0);
	const std::string stats = readText(out + "/stats.json");
	const auto [code, text] = finish(spawnEsif(runArgs("dslam.ini", kRawlog, out), 64 * 1024));
	EXPECT_EQ(code, 1) << text;
	EXPECT_EQ(errorLines(text).size(), 1u) << text;
	EXPECT_EQ(readText(out + "/stats.json"), stats) << "the previous run's folder is intact";
	EXPECT_FALSE(fs::exists(out + "/info_matrix.png")) << "nothing of the failed run in it";
	EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(RunFolder, ReRunWithAnotherPluginLeavesNoStaleFile)
{
	TempDir dir;
	const std::string out = dir.file("out");
	ASSERT_EQ(runToEnd(runArgs("dslam.ini", kRawlog, out)).first, 0);
	ASSERT_TRUE(fs::exists(out + "/info_matrix.png"));	// D-SLAM has an information matrix
	const auto [code, text] = runToEnd(runArgs("ekf.ini", kRawlog, out));
	ASSERT_EQ(code, 0) << text;
	EXPECT_FALSE(fs::exists(out + "/info_matrix.png")) << "the EKF has none: the D-SLAM run's must not survive";
	EXPECT_NE(readText(out + "/stats.json").find("\"EkfSlam\""), std::string::npos);
	EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(RunFolder, ASecondWriterFailsAtOnceNamingTheFolder)
{
	TempDir dir;
	const std::string out = dir.file("out");
	// The lock a running esif holds, held here instead.
	const int fd = ::open(dir.file(".out.lock").c_str(), O_RDWR | O_CREAT, 0644);
	ASSERT_GE(fd, 0);
	ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
	const auto [code, text] = runToEnd(runArgs("ekf.ini", kRawlog, out));
	::close(fd);
	EXPECT_EQ(code, 1) << text;
	const auto errors = errorLines(text);
	ASSERT_EQ(errors.size(), 1u) << text;
	EXPECT_NE(errors[0].find(out + ": another esif process is writing this folder"), std::string::npos) << text;
	EXPECT_FALSE(fs::exists(out));
}

TEST(RunFolder, TwoRunsIntoOneFolderOneFailsOnTheLock)
{
	TempDir dir;
	const std::string out = dir.file("out");
	// The first run is long, so it still holds the lock when the second
	// starts, however loaded the machine; it is then stopped.
	const auto first = spawnEsif(runArgs("ekf.ini", longRawlog(dir), out));
	ASSERT_FALSE(waitForPartial(dir.path(), ".out.partial-").empty());
	const auto [second_code, second_text] = runToEnd(runArgs("ekf.ini", kRawlog, out));
	::kill(first.pid, SIGTERM);
	const auto [first_code, first_text] = finish(first);
	EXPECT_EQ(second_code, 1) << second_text;
	EXPECT_EQ(errorLines(second_text).size(), 1u) << second_text;
	EXPECT_NE(second_text.find(out + ": another esif process is writing this folder"), std::string::npos)
		<< second_text;
	EXPECT_EQ(first_code, 128 + SIGTERM) << first_text;
	EXPECT_FALSE(fs::exists(out)) << "neither run left a folder";
	EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(RunFolder, RefusesToReplaceAUsersFolder)
{
	TempDir dir;
	const std::string out = dir.file("mine");
	fs::create_directory(out);
	std::ofstream(out + "/notes.txt") << "keep me\n";
	const auto [code, text] = runToEnd(runArgs("ekf.ini", kRawlog, out));
	EXPECT_EQ(code, 1) << text;
	const auto errors = errorLines(text);
	ASSERT_EQ(errors.size(), 1u) << text;
	EXPECT_NE(errors[0].find(out + ": not empty and not an esif output folder"), std::string::npos) << text;
	EXPECT_EQ(readText(out + "/notes.txt"), "keep me\n");
	EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(RunFolder, StalePartialFoldersOfAKilledWriterAreRemoved)
{
	TempDir dir;
	const std::string out = dir.file("out");
	fs::create_directories(dir.file(".out.partial-999999/sub"));
	std::ofstream(dir.file(".out.partial-999999/sub/stats.json")) << "{}";
	const auto [code, text] = runToEnd(runArgs("ekf.ini", kRawlog, out));
	EXPECT_EQ(code, 0) << text;
	EXPECT_TRUE(leftovers(dir.path()).empty());
	EXPECT_TRUE(fs::exists(out + "/.esif-output"));
}

TEST(RunFolder, ReadOnlyParentIsOneLineNamingTheCause)
{
	TempDir dir;
	// root writes into a folder whatever its mode: then use /sys, where even
	// root cannot create files.
	const bool root = ::geteuid() == 0;
	const std::string parent = root ? "/sys" : dir.file("ro");
	if (!root)
	{
		fs::create_directory(parent);
		fs::permissions(parent, fs::perms::owner_read | fs::perms::owner_exec);
	}
	const std::string probe = parent + "/.esif_probe";
	const int fd = ::open(probe.c_str(), O_RDWR | O_CREAT, 0644);
	const int err = errno;
	if (fd >= 0)
	{
		::close(fd);
		::unlink(probe.c_str());
		GTEST_SKIP() << parent << " is writable here";
	}
	const std::string out = parent + "/esif_test_out";
	const auto [code, text] = runToEnd(runArgs("ekf.ini", kRawlog, out));
	if (!root) fs::permissions(parent, fs::perms::owner_all);
	EXPECT_EQ(code, 1) << text;
	const auto errors = errorLines(text);
	ASSERT_EQ(errors.size(), 1u) << text;
	EXPECT_NE(errors[0].find(out + ": "), std::string::npos) << text;
	EXPECT_NE(errors[0].find(std::strerror(err)), std::string::npos) << "the real cause: " << text;
}

TEST(RunFolder, SigtermDuringAReRunKeepsThePreviousFolderAndLeavesNothing)
{
	TempDir dir;
	const std::string out = dir.file("out");
	ASSERT_EQ(runToEnd(runArgs("ekf.ini", kRawlog, out)).first, 0);
	const std::string stats = readText(out + "/stats.json");
	const std::string rawlog = longRawlog(dir);
	const auto child = spawnEsif(runArgs("ekf.ini", rawlog, out));
	ASSERT_FALSE(waitForPartial(dir.path(), ".out.partial-").empty());
	std::this_thread::sleep_for(std::chrono::milliseconds(300));  // into the replay
	::kill(child.pid, SIGTERM);
	const auto [code, text] = finish(child);
	EXPECT_EQ(code, 128 + SIGTERM) << text;
	EXPECT_EQ(readText(out + "/stats.json"), stats);
	EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(RunFolder, SigtermDuringTheReplaySaysHowFarItGot)
{
	// A run stopped by a time limit (bench/city_scale.sh's timeout) or by
	// the user says which step it had reached, in one line on stderr.
	TempDir dir;
	const std::string out = dir.file("out");
	const auto child = spawnEsif(runArgs("ekf.ini", longRawlog(dir), out));
	ASSERT_FALSE(waitForPartial(dir.path(), ".out.partial-").empty());
	// Well into the replay, which takes about 20 s: reading the rawlog and
	// starting the plugin take 0.1-0.5 s here, more on a loaded machine.
	std::this_thread::sleep_for(std::chrono::seconds(2));
	::kill(child.pid, SIGTERM);
	const auto [code, text] = finish(child);
	EXPECT_EQ(code, 128 + SIGTERM) << text;
	std::smatch m;
	ASSERT_TRUE(std::regex_search(
		text, m, std::regex("esif: esif::EkfSlam stopped by signal 15 after ([0-9]+) of ([0-9]+) steps, [0-9.]+ s into the replay\n")))
		<< text;
	EXPECT_LT(std::stoul(m[1]), std::stoul(m[2])) << text;
	EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(RunFolder, SigtermDuringCompareStopsTheRunAndLeavesNothing)
{
	TempDir dir;
	const std::string rawlog = longRawlog(dir);
	// Orphans of compare would become this process's children: none may be left.
	ASSERT_EQ(::prctl(PR_SET_CHILD_SUBREAPER, 1), 0);
	const std::string out = dir.file("cmp");
	const auto compare = spawnEsif({"compare", "--configs", sourcePath("configs/ekf.ini"), "--rawlog", rawlog, "--out", out});
	const std::string partial = waitForPartial(dir.path(), ".cmp.partial-");
	ASSERT_FALSE(partial.empty());
	ASSERT_FALSE(waitForPartial(partial, ".ekf.partial-").empty()) << "the child run started";
	std::this_thread::sleep_for(std::chrono::milliseconds(300));
	::kill(compare.pid, SIGTERM);
	const auto [code, text] = finish(compare);
	EXPECT_EQ(code, 128 + SIGTERM) << text;
	int status = 0;
	EXPECT_EQ(::waitpid(-1, &status, WNOHANG), -1) << "no orphaned child run";
	EXPECT_EQ(errno, ECHILD);
	EXPECT_FALSE(fs::exists(out));
	EXPECT_TRUE(leftovers(dir.path()).empty());
}

}  // namespace
