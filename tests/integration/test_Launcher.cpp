/// \file test_Launcher.cpp
/// The `esif` launcher (framework/app/launcher): --help without the host,
/// `esif plugins` from the plugin cache exactly as the host lists it, and a
/// cache that is out of date (a library touched, a plugin added, the file
/// damaged) never used. The stale-cache cases run on a copy of the build's
/// bin/ and lib/ in a temporary folder, whose cache carries a marker line:
/// the marker shows whether the launcher answered from it.

#include "EsifTestSupport.h"

#include <esif/core/Text.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace esif;
using namespace esif::test;

namespace
{
const fs::path kBuild = fs::path(ESIF_BINARY).parent_path().parent_path();

/// A copy of the build's launcher, host libraries, plugins and cache, with
/// modification times kept, so that the copied cache is current for it.
struct CopiedInstall
{
	TempDir dir;
	std::string esif;
	CopiedInstall()
	{
		const fs::path root = dir.path();
		fs::create_directories(root / "bin");
		fs::create_directories(root / "lib" / "esif");
		const auto copy = [](const fs::path& from, const fs::path& to) {
			fs::copy_file(from, to);
			fs::last_write_time(to, fs::last_write_time(from));
		};
		copy(ESIF_BINARY, root / "bin" / "esif");
		for (const auto& e : fs::directory_iterator(kBuild / "lib"))
			if (e.is_regular_file() && e.path().extension() == ".so") copy(e.path(), root / "lib" / e.path().filename());
		for (const auto& e : fs::directory_iterator(kBuild / "lib" / "esif"))
			if (e.is_regular_file()) copy(e.path(), root / "lib" / "esif" / e.path().filename());
		esif = (root / "bin" / "esif").string();
	}
	std::string cache() const { return dir.file("lib/esif/plugins.cache"); }

	/// The cache for this folder (its own paths) with `marker` as the
	/// listing's last line.
	void writeMarkedCache(const std::string& marker) const
	{
		std::string text = readText(cache());
		text = replaceAll(text, "folder " + (kBuild / "lib").string() + "\n", "folder " + dir.file("lib") + "\n");
		text = replaceAll(text, (kBuild / "lib" / "esif").string(), dir.file("lib/esif"));
		const auto at = text.find("\nlisting ");
		const auto body = text.find('\n', at + 1) + 1;
		std::string listing = text.substr(body) + marker + "\n";
		text = text.substr(0, at) + "\nlisting " + std::to_string(listing.size()) + "\n" + listing;
		std::ofstream(cache(), std::ios::binary | std::ios::trunc) << text;
	}
};

bool answeredFromCache(const CommandResult& r) { return r.out.find("MARKER-FROM-CACHE") != std::string::npos; }
}  // namespace

TEST(Launcher, HelpListsEveryCommandWithoutTheHost)
{
	const CopiedInstall install;
	fs::remove(install.dir.file("lib/libesif_app.so"));	 // --help must not need it
	const auto r = runShell(quoted(install.esif) + " --help");
	EXPECT_EQ(r.exit_code, 0) << r.out;
	for (const char* command : {"run", "compare", "simulate", "import", "export", "plugins", "localmaps", "montecarlo", "bench"})
		EXPECT_NE(r.out.find("  " + std::string(command) + " "), std::string::npos) << command << "\n" << r.out;
	const auto run = runShell(quoted(install.esif) + " run --help");
	EXPECT_EQ(run.exit_code, 4) << run.out;
	EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 1) << "one line naming the missing host: " << run.out;
	EXPECT_NE(run.out.find("libesif_app.so"), std::string::npos) << run.out;
}

TEST(Launcher, PluginsFromTheCacheEqualTheHostsListing)
{
	ASSERT_TRUE(fs::exists(kBuild / "lib" / "esif" / "plugins.cache")) << "the build writes it (esif_plugin_cache)";
	const auto cached = runShell(quoted(ESIF_BINARY) + " plugins");
	const auto live = runShell("ESIF_PLUGIN_CACHE=0 " + quoted(ESIF_BINARY) + " plugins");
	EXPECT_EQ(cached.exit_code, 0);
	EXPECT_EQ(live.exit_code, 0);
	EXPECT_EQ(cached.out, live.out);
	EXPECT_NE(live.out.find("EkfSlam"), std::string::npos) << live.out;
}

TEST(Launcher, ACurrentCacheAnswersAndAStaleOneIsNeverUsed)
{
	const CopiedInstall install;
	install.writeMarkedCache("MARKER-FROM-CACHE");
	const std::string plugins = quoted(install.esif) + " plugins";
	ASSERT_TRUE(answeredFromCache(runShell(plugins))) << "the copy's cache is current";
	EXPECT_FALSE(answeredFromCache(runShell("ESIF_PLUGIN_CACHE=0 " + plugins)));
	EXPECT_FALSE(answeredFromCache(runShell("ESIF_PLUGIN_PATH=" + quoted(install.dir.path()) + " " + plugins)));
	EXPECT_FALSE(answeredFromCache(runShell(plugins + " --plugin-dir " + quoted(install.dir.path()))));

	// A rebuilt plugin (new modification time): the host lists it.
	const fs::path ekf = install.dir.file("lib/esif/libesif_plugin_ekf.so");
	fs::last_write_time(ekf, fs::last_write_time(ekf) + std::chrono::seconds(1));
	const auto touched = runShell(plugins);
	EXPECT_EQ(touched.exit_code, 0) << touched.out;
	EXPECT_FALSE(answeredFromCache(touched));
	EXPECT_NE(touched.out.find("EkfSlam"), std::string::npos) << touched.out;
	EXPECT_NE(touched.out.find("Plugin folders searched: " + install.dir.file("lib/esif")), std::string::npos)
		<< touched.out;
}

TEST(Launcher, AnAddedOrRemovedPluginOrADamagedCacheIsNotUsed)
{
	const CopiedInstall install;
	const std::string plugins = quoted(install.esif) + " plugins";
	install.writeMarkedCache("MARKER-FROM-CACHE");
	fs::remove(install.dir.file("lib/esif/libesif_plugin_dslam.so"));
	const auto removed = runShell(plugins);
	EXPECT_FALSE(answeredFromCache(removed));
	EXPECT_EQ(removed.out.find("\nDslam "), std::string::npos) << removed.out;

	const CopiedInstall second;
	second.writeMarkedCache("MARKER-FROM-CACHE");
	fs::copy_file(second.dir.file("lib/esif/libesif_plugin_ekf.so"), second.dir.file("lib/esif/libesif_plugin_ekf2.so"));
	EXPECT_FALSE(answeredFromCache(runShell(quoted(second.esif) + " plugins")));

	const CopiedInstall third;
	third.writeMarkedCache("MARKER-FROM-CACHE");
	std::string text = readText(third.cache());
	std::ofstream(third.cache(), std::ios::binary | std::ios::trunc) << text.substr(0, text.size() - 40);
	const auto damaged = runShell(quoted(third.esif) + " plugins");
	EXPECT_EQ(damaged.exit_code, 0) << damaged.out;
	EXPECT_FALSE(answeredFromCache(damaged));
}
