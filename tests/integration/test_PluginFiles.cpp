// Plugin files and the plugin cache are opened only as regular files of a
// bounded size, and a plugin is mapped only from a sealed copy checked
// first: a plugin file cut short (an interrupted copy) or a FIFO named like
// a plugin is a warning, the others still load; a FIFO, /dev/zero or a huge
// file as the cache is not waited for nor read without end; and a cache is
// not used once what the plugins load has changed (the loader's
// environment, a system library).

#include <EsifTestSupport.h>

#include <esif/core/Text.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sys/stat.h>

namespace fs = std::filesystem;

namespace
{
using esif::test::quoted;
using esif::test::readText;
using esif::test::runShell;
using esif::test::simulateSmall;
using esif::test::sourcePath;
using esif::test::TempDir;

const fs::path kBuild = fs::path(ESIF_BINARY).parent_path().parent_path();

/// A folder with a copy of a real plugin cut at 30,000 bytes (its segments
/// reach further) and a FIFO named like a plugin.
std::string brokenPluginFolder(const TempDir& dir)
{
	const std::string folder = dir.file("broken");
	fs::create_directory(folder);
	const std::string whole = readText((kBuild / "lib" / "esif" / "libesif_plugin_ekf.so").string());
	std::ofstream(folder + "/libesif_plugin_cut.so", std::ios::binary) << whole.substr(0, 30000);
	::mkfifo((folder + "/libesif_plugin_fifo.so").c_str(), 0644);
	return folder;
}

/// `command` under a 60 s timeout (124 when it hangs), output merged.
esif::test::CommandResult bounded(const std::string& command) { return runShell("timeout 60 " + command); }

TEST(PluginFiles, ACutPluginAndAFifoAreWarningsAndTheOthersStillLoad)
{
	TempDir dir;
	const std::string folder = brokenPluginFolder(dir);
	const auto r = bounded(quoted(ESIF_BINARY) + " plugins --plugin-dir " + quoted(folder));
	EXPECT_EQ(r.exit_code, 0) << r.out;
	EXPECT_NE(r.out.find("esif: warning: " + folder + "/libesif_plugin_cut.so: cannot load plugin, skipped (cut short: "
						 "segment"),
			  std::string::npos)
		<< r.out;
	EXPECT_NE(r.out.find(", the file has 30000)"), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("esif: warning: " + folder + "/libesif_plugin_fifo.so: cannot load plugin, skipped (not a "
						 "regular file"),
			  std::string::npos)
		<< r.out;
	EXPECT_NE(r.out.find("EkfSlam    ("), std::string::npos) << r.out;

	// A run with the broken folder on ESIF_PLUGIN_PATH completes, and leaves no partial folder or lock.
	ASSERT_EQ(simulateSmall(dir.file("s.rawlog")).exit_code, 0);
	const auto run = bounded(
		"env ESIF_PLUGIN_PATH=" + quoted(folder) + " " + quoted(ESIF_BINARY) + " run -q --config " +
		quoted(sourcePath("configs/ekf.ini")) + " --rawlog " + quoted(dir.file("s.rawlog")) + " --out " +
		quoted(dir.file("o")));
	EXPECT_EQ(run.exit_code, 0) << run.out;
	for (const auto& e : fs::directory_iterator(dir.path()))
		EXPECT_NE(e.path().filename().string().rfind(".o.", 0), 0u) << e.path();
}

/// A copy of the build's launcher, libraries, plugins and cache (modification
/// times kept, so that the cache is current for it, its folder line set to
/// the copy's).
struct CopiedInstall
{
	TempDir dir;
	std::string esif;
	CopiedInstall()
	{
		const auto copied = runShell(
			"cp -a " + quoted((kBuild / "bin").string()) + " " + quoted((kBuild / "lib").string()) + " " +
			quoted(dir.path()));
		EXPECT_EQ(copied.exit_code, 0) << copied.out;
		std::string cache = readText(cacheFile());
		cache = esif::replaceAll(cache, "folder " + (kBuild / "lib").string() + "\n", "folder " + dir.file("lib") + "\n");
		std::ofstream(cacheFile(), std::ios::binary | std::ios::trunc) << cache;
		esif = dir.file("bin/esif");
	}
	std::string cacheFile() const { return dir.file("lib/esif/plugins.cache"); }
};

TEST(PluginFiles, TheCacheIsNotUsedOnceWhatThePluginsLoadChanged)
{
	const CopiedInstall install;
	const auto plain = bounded(quoted(install.esif) + " plugins");
	ASSERT_EQ(plain.exit_code, 0) << plain.out;
	ASSERT_NE(plain.out.find("CeresFullSlam"), std::string::npos) << plain.out;
	// A broken libglog.so.1 first on the loader's path: ceres_full no longer loads, and
	// the listing says so (the cache knew nothing of glog).
	fs::create_directory(install.dir.file("fake"));
	std::ofstream(install.dir.file("fake/libglog.so.1")) << "";
	const auto r = bounded("env LD_LIBRARY_PATH=" + quoted(install.dir.file("fake")) + " " + quoted(install.esif) + " plugins");
	EXPECT_EQ(r.exit_code, 0) << r.out;
	EXPECT_EQ(r.out.find("CeresFullSlam    ("), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("libesif_plugin_ceres_full.so: cannot load plugin, skipped"), std::string::npos) << r.out;
}

TEST(PluginFiles, AFifoDevZeroOrHugeFileAsTheCacheIsNeitherWaitedForNorRead)
{
	const CopiedInstall install;
	const std::string cache = install.cacheFile();
	// Under a 768 MiB address-space limit (the host and its libraries map
	// about 500): /dev/zero read line by line would exhaust it, and a FIFO
	// would keep `esif plugins` waiting until the timeout.
	const auto listed = [&](const std::string& what) {
		const auto start = std::chrono::steady_clock::now();
		const auto r =
			bounded("prlimit --as=" + std::to_string(std::size_t{768} << 20) + " " + quoted(install.esif) + " plugins");
		const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
		EXPECT_EQ(r.exit_code, 0) << what << ": " << r.out;
		EXPECT_NE(r.out.find("EkfSlam    ("), std::string::npos) << what << ": " << r.out;
		EXPECT_LT(seconds, 20.0) << what;
	};
	fs::remove(cache);
	ASSERT_EQ(::mkfifo(cache.c_str(), 0644), 0);
	listed("a FIFO");
	fs::remove(cache);
	fs::create_symlink("/dev/zero", cache);
	listed("/dev/zero");
	fs::remove(cache);
	std::ofstream(cache, std::ios::binary) << "esif plugin cache 2\n";
	fs::resize_file(cache, std::uintmax_t{1} << 30);  // then one line of a GiB of zeros (sparse)
	listed("a 1 GiB cache");
}

}  // namespace
