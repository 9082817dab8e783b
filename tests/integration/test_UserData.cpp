// esif never destroys a user's data: an output folder is replaced only while
// it holds nothing but what its marker says esif wrote there, no output may
// be, hold or lie inside an input, and a campaign's names never reach
// outside --out. Each refusal is one error line with exit 1 and leaves
// every file as it was.

#include <EsifTestSupport.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace
{
using esif::test::expectOneErrorLine;
using esif::test::quoted;
using esif::test::readText;
using esif::test::runEsif;
using esif::test::simulateSmall;
using esif::test::sourcePath;
using esif::test::TempDir;

std::string runArgs(const std::string& rawlog, const std::string& out)
{
	return "run -q --config " + quoted(sourcePath("configs/ekf.ini")) + " --rawlog " + quoted(rawlog) + " --out " +
		   quoted(out);
}

/// A small simulated rawlog (200 steps) in `dir`, shared by the tests of a suite.
class UserData : public ::testing::Test
{
   protected:
	static void SetUpTestSuite()
	{
		dir_ = new TempDir;
		const auto r = simulateSmall(rawlog());
		ASSERT_EQ(r.exit_code, 0) << r.out;
	}
	static void TearDownTestSuite()
	{
		delete dir_;
		dir_ = nullptr;
	}
	static std::string rawlog() { return dir_->file("small.rawlog"); }

	static TempDir* dir_;
};
TempDir* UserData::dir_ = nullptr;

/// A name that looks like esif's output is no proof that the folder is
/// esif's: without the marker, nothing is replaced.
TEST_F(UserData, AFolderWithoutTheMarkerIsNeverReplacedWhateverItsFilesAreNamed)
{
	for (const std::string look_alike : {"stats.json", "comparison.csv", "localmap_1.txt"})
	{
		TempDir dir;
		const std::string out = dir.file("U");
		fs::create_directory(out);
		std::ofstream(out + "/important.txt") << "x\n";
		std::ofstream(out + "/" + look_alike) << "{}\n";
		expectOneErrorLine(runEsif(runArgs(rawlog(), out)), out + ": not empty and not an esif output folder");
		EXPECT_EQ(readText(out + "/important.txt"), "x\n") << look_alike;
		EXPECT_EQ(readText(out + "/" + look_alike), "{}\n") << look_alike;
	}
}

/// esif's own folder with a file the user put there later: refused, naming
/// that file; once the file is gone the folder is replaced again.
TEST_F(UserData, AnEsifFolderHoldingAForeignFileIsRefusedNamingIt)
{
	TempDir dir;
	const std::string out = dir.file("run");
	ASSERT_EQ(runEsif(runArgs(rawlog(), out)).exit_code, 0);
	const std::string marker = readText(out + "/.esif-output");
	EXPECT_EQ(marker.rfind("esif output folder\n", 0), 0u) << marker;
	for (const std::string written : {"\nstats.json\n", "\nlandmarks.txt\n", "\nmap.png\n", "\nparams.ini\n"})
		EXPECT_NE(marker.find(written), std::string::npos) << "the marker lists" << written << marker;

	fs::create_directory(out + "/notes");
	std::ofstream(out + "/notes/mine.txt") << "keep me\n";
	expectOneErrorLine(runEsif(runArgs(rawlog(), out)), out + "/notes/: not written by esif");
	fs::remove(out + "/notes/mine.txt");
	expectOneErrorLine(runEsif(runArgs(rawlog(), out)), out + "/notes/: not written by esif");
	fs::remove(out + "/notes");
	std::ofstream(out + "/stats.json.orig") << "mine\n";
	expectOneErrorLine(runEsif(runArgs(rawlog(), out)), out + "/stats.json.orig: not written by esif");
	EXPECT_EQ(readText(out + "/stats.json.orig"), "mine\n");
	fs::remove(out + "/stats.json.orig");
	const auto r = runEsif(runArgs(rawlog(), out));
	EXPECT_EQ(r.exit_code, 0) << r.out;
}

/// The marker of an esif that did not list its files proves nothing about them.
TEST_F(UserData, AMarkerWithoutAListOfFilesReplacesNothing)
{
	TempDir dir;
	const std::string out = dir.file("old");
	fs::create_directory(out);
	std::ofstream(out + "/.esif-output") << "esif output folder\n";
	std::ofstream(out + "/stats.json") << "{}\n";
	expectOneErrorLine(runEsif(runArgs(rawlog(), out)), "the folder's marker lists nothing (an earlier esif)");
	EXPECT_EQ(readText(out + "/stats.json"), "{}\n");
}

/// A comparison's marker lists its runs' files too, so it is replaced as a whole.
TEST_F(UserData, ACompareFolderIsReplacedAndAForeignFileInARunRefusesIt)
{
	TempDir dir;
	const std::string out = dir.file("cmp");
	const std::string args = "compare --configs " + quoted(sourcePath("configs/ekf.ini")) + " --rawlog " +
							 quoted(rawlog()) + " --out " + quoted(out);
	ASSERT_EQ(runEsif(args).exit_code, 0);
	EXPECT_NE(readText(out + "/.esif-output").find("\nekf/stats.json\n"), std::string::npos);
	ASSERT_EQ(runEsif(args).exit_code, 0) << "re-run into its own folder";
	std::ofstream(out + "/ekf/extra.csv") << "1\n";
	expectOneErrorLine(runEsif(args), out + "/ekf/extra.csv: not written by esif");
	EXPECT_EQ(readText(out + "/ekf/extra.csv"), "1\n");
}

TEST_F(UserData, AnOutputFolderIsNeverAnInputFolderOrAroundAnInput)
{
	TempDir dir;
	// The rawlog inside --out: replacing --out would delete it.
	const std::string data = dir.file("data");
	fs::create_directory(data);
	fs::copy_file(rawlog(), data + "/small.rawlog");
	expectOneErrorLine(runEsif(runArgs(data + "/small.rawlog", data)), data + ": --out holds the rawlog");
	expectOneErrorLine(runEsif(runArgs(data + "/small.rawlog", data + "/./")), "--out holds the rawlog");
	EXPECT_TRUE(fs::exists(data + "/small.rawlog"));
	// --out inside the config's folder is fine; --out being the config is not.
	const std::string config = dir.file("ekf.ini");
	fs::copy_file(sourcePath("configs/ekf.ini"), config);
	expectOneErrorLine(
		runEsif("run -q --config " + quoted(config) + " --rawlog " + quoted(rawlog()) + " --out " + quoted(config)),
		config + ": --out is the config");
	EXPECT_EQ(readText(config), readText(sourcePath("configs/ekf.ini")));
}

/// A local-map folder is an input of a run and may not be its output; a
/// folder of the authors' maps is not esif's, so `localmaps build` never
/// replaces it (it used to delete its linear_slam_result/).
TEST_F(UserData, LocalMapFoldersAreNeverReplacedByARunOrABuild)
{
	TempDir dir;
	const std::string maps = dir.file("maps");
	ASSERT_EQ(runEsif("localmaps build --config " + quoted(sourcePath("configs/slsjf.ini")) + " --rawlog " +
					  quoted(rawlog()) + " --out " + quoted(maps))
				  .exit_code,
			  0);
	const std::string first_map = readText(maps + "/localmap_1.txt");
	expectOneErrorLine(
		runEsif("run -q --config " + quoted(sourcePath("configs/localmaps/slsjf.ini")) + " --local-maps " +
				quoted(maps) + " --out " + quoted(maps)),
		maps + ": --out is the local-map folder");
	EXPECT_EQ(readText(maps + "/localmap_1.txt"), first_map);

	const std::string authors = dir.file("authors");
	fs::create_directories(authors + "/linear_slam_result");
	fs::copy_file(maps + "/localmap_1.txt", authors + "/localmap_1.txt");
	std::ofstream(authors + "/linear_slam_result/feature.txt") << "1 0 0\n";
	expectOneErrorLine(
		runEsif("localmaps build --config " + quoted(sourcePath("configs/slsjf.ini")) + " --rawlog " +
				quoted(rawlog()) + " --out " + quoted(authors)),
		authors + ": not empty and not an esif output folder");
	EXPECT_EQ(readText(authors + "/linear_slam_result/feature.txt"), "1 0 0\n");
}

/// A file output named like its input is refused before anything is read
/// or written: the input stays byte for byte.
TEST_F(UserData, AFileOutputIsNeverItsInput)
{
	TempDir dir;
	const std::string vp = dir.file("vp.txt");
	std::ofstream(vp) << "ODOMETRY 0 1 0.1 0 0 1 0 0 1 0 1\n";
	expectOneErrorLine(runEsif("import victoria-park --in " + quoted(vp) + " --out " + quoted(vp)), vp + ": --out is the dataset");
	EXPECT_EQ(readText(vp), "ODOMETRY 0 1 0.1 0 0 1 0 0 1 0 1\n");

	const std::string log = dir.file("log.rawlog");
	fs::copy_file(rawlog(), log);
	const std::string before = readText(log);
	expectOneErrorLine(runEsif("export g2o --rawlog " + quoted(log) + " --out " + quoted(log)), log + ": --out is the rawlog");
	EXPECT_EQ(readText(log), before);

	const std::string scenario = dir.file("s.ini");
	fs::copy_file(sourcePath("configs/sim/small.ini"), scenario);
	expectOneErrorLine(runEsif("simulate --config " + quoted(scenario) + " --out " + quoted(scenario)),
				  scenario + ": --out is the scenario");
	// The ground truth written beside the rawlog may not be the scenario either.
	const std::string truth_named = dir.file("t_ground_truth.txt");
	fs::copy_file(scenario, truth_named);
	expectOneErrorLine(runEsif("simulate --config " + quoted(truth_named) + " --out " + quoted(dir.file("t.rawlog"))),
				  "is the scenario");
	EXPECT_EQ(readText(scenario), readText(sourcePath("configs/sim/small.ini")));

	// import g2o: the solution's folder may not hold the g2o file.
	const std::string solved = dir.file("solved");
	fs::create_directory(solved);
	ASSERT_EQ(runEsif("export g2o --rawlog " + quoted(log) + " --out " + quoted(solved + "/p.g2o")).exit_code, 0);
	expectOneErrorLine(
		runEsif("import g2o --g2o " + quoted(solved + "/p.g2o") + " --rawlog " + quoted(log) + " --out " + quoted(solved)),
		solved + ": --out holds the g2o file");
	EXPECT_TRUE(fs::exists(solved + "/p.g2o"));
}

/// Names read from campaign.ini become folder names under runs/ and
/// failures/: one that reaches outside the campaign is refused.
TEST_F(UserData, ACampaignNameNeverReachesOutsideItsFolder)
{
	TempDir dir;
	const std::string campaign = dir.file("mc");
	fs::create_directory(campaign);
	const std::string scenario = sourcePath("configs/sim/small.ini"), config = sourcePath("configs/ekf.ini");
	for (const std::string name : {"../../x", "a/b", "..", ".hidden", ""})
	{
		std::ofstream(campaign + "/campaign.ini") << "[montecarlo]\nscenario = " << scenario << "\nseed0 = 1\nruns = 1\n"
												  << "configs = " << config << "\nnames = " << name << "\n";
		const auto r = runEsif("montecarlo --scenario " + quoted(scenario) + " --configs " + quoted(config) +
							   " --runs 1 --out " + quoted(campaign));
		expectOneErrorLine(r, campaign + "/campaign.ini: [montecarlo] names");
		expectOneErrorLine(runEsif("montecarlo --collect " + quoted(campaign)), "[montecarlo] names");
	}
	EXPECT_FALSE(fs::exists(dir.file("x"))) << "nothing written outside --out";
	EXPECT_FALSE(fs::exists(campaign + "/runs"));

	// The campaign folder may not hold the scenario or a config.
	const std::string holder = dir.file("holder");
	fs::create_directory(holder);
	fs::copy_file(scenario, holder + "/s.ini");
	expectOneErrorLine(runEsif("montecarlo --scenario " + quoted(holder + "/s.ini") + " --configs " + quoted(config) +
						  " --runs 1 --out " + quoted(holder)),
				  holder + ": --out holds the scenario");
}

}  // namespace
