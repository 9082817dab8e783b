// Side inputs (ground truth, associations, local maps, reference results,
// g2o solutions, scenarios, campaign files, the command line) are held to
// the rawlog's standard: every count is bounded before it is allocated,
// every value is finite and plausible, a file where a folder belongs (or a
// loop of links, or a device) is named, and nothing is silently ignored.
// Each case is one error line naming the file (and line) with exit 1.

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

/// A simulated rawlog (200 steps, ground truth beside it) and local maps
/// built from it, copied per test where a test damages them.
class SideInputs : public ::testing::Test
{
   protected:
	static void SetUpTestSuite()
	{
		dir_ = new TempDir;
		ASSERT_EQ(simulateSmall(dir_->file("small.rawlog")).exit_code, 0);
		const auto r = runEsif("localmaps build --config " + quoted(sourcePath("configs/slsjf.ini")) + " --rawlog " +
							   quoted(dir_->file("small.rawlog")) + " --out " + quoted(dir_->file("maps")));
		ASSERT_EQ(r.exit_code, 0) << r.out;
	}
	static void TearDownTestSuite()
	{
		delete dir_;
		dir_ = nullptr;
	}

	/// A copy of the rawlog and its ground truth in `dir` as NAME.rawlog.
	static std::string rawlogCopy(const TempDir& dir, const std::string& name = "log")
	{
		fs::copy_file(dir_->file("small.rawlog"), dir.file(name + ".rawlog"));
		for (const std::string suffix : {"_ground_truth.txt", "_ground_truth_robot_path.txt"})
			fs::copy_file(dir_->file("small" + suffix), dir.file(name + suffix));
		return dir.file(name + ".rawlog");
	}
	static std::string mapsCopy(const TempDir& dir)
	{
		fs::copy(dir_->file("maps"), dir.file("maps"));
		fs::remove(dir.file("maps/.esif-output"));
		return dir.file("maps");
	}
	static std::string run(const std::string& config, const std::string& rawlog, const std::string& out)
	{
		return "run -q --config " + quoted(config) + " --rawlog " + quoted(rawlog) + " --out " + quoted(out);
	}
	static std::string runOnMaps(const std::string& maps, const std::string& out, const std::string& extra = "")
	{
		return "run -q --config " + quoted(sourcePath("configs/localmaps/slsjf.ini")) + " --local-maps " + quoted(maps) +
			   " " + extra + " --out " + quoted(out);
	}

	static TempDir* dir_;
};
TempDir* SideInputs::dir_ = nullptr;

const std::string kEkf = sourcePath("configs/ekf.ini");

// ------------------------------------------------------------ bounded counts

/// A 16-byte measurement-IDs file naming step 10^9 used to end in
/// std::bad_alloc (exit 4) after allocating gigabytes.
TEST_F(SideInputs, MeasurementIdsBeyondTheRawlogsStepsAreRefusedAtTheirLine)
{
	TempDir dir;
	const std::string log = rawlogCopy(dir);
	for (const std::string step : {"100000000", "1000000000", "200"})
	{
		std::ofstream(dir.file("log_ground_truth_measurement_ids.txt")) << step << " 0 5 5\n";
		expectOneErrorLine(runEsif(run(kEkf, log, dir.file("out"))),
					  "log_ground_truth_measurement_ids.txt:1: step " + step + " but the rawlog has 200 steps");
	}
	EXPECT_FALSE(fs::exists(dir.file("out")));
}

TEST_F(SideInputs, AssociationsDeclaringOtherStepsAreRefusedBeforeAllocating)
{
	TempDir dir;
	fs::create_directory(dir.file("assoc"));
	std::ofstream(dir.file("c.ini")) << "[esif]\nplugin = EkfSlam\nassociations_from = " << dir.file("assoc") << "\n";
	for (const std::string steps : {"100000000", "18446744073709551615"})
	{
		std::ofstream(dir.file("assoc/associations.txt")) << "# steps " << steps << "\n";
		expectOneErrorLine(runEsif(run(dir.file("c.ini"), dir_->file("small.rawlog"), dir.file("out"))),
					  "associations.txt:1: recorded for " + steps + " steps, the rawlog has 200");
	}
	std::ofstream(dir.file("assoc/associations.txt")) << "# steps 200\n0 0 matched -5\n";
	expectOneErrorLine(runEsif(run(dir.file("c.ini"), dir_->file("small.rawlog"), dir.file("out"))),
				  "associations.txt:2: landmark_id -5 is not a landmark ID");
}

/// [esif] initial_run is read by the host, which hands the estimate to the
/// plugin: a plugin that starts from none refuses the key, a folder that is
/// no run or a run of fewer steps is named before the replay, and a run
/// folder of the same rawlog is accepted.
TEST_F(SideInputs, AnInitialRunIsReadByTheHostAndCheckedBeforeTheReplay)
{
	TempDir dir;
	ASSERT_EQ(runEsif(run(kEkf, dir_->file("small.rawlog"), dir.file("ekf"))).exit_code, 0);
	const auto config = [&](const std::string& plugin, const std::string& folder) {
		std::ofstream(dir.file("c.ini")) << "[esif]\nplugin = " << plugin << "\ninitial_run = " << folder << "\n";
		return dir.file("c.ini");
	};
	expectOneErrorLine(runEsif(run(config("EkfSlam", dir.file("ekf")), dir_->file("small.rawlog"), dir.file("out"))),
					   "[esif] initial_run: plugin EkfSlam does not start from another run's estimate");
	expectOneErrorLine(
		runEsif(run(config("CeresFullSlam", dir.file("nowhere")), dir_->file("small.rawlog"), dir.file("out"))),
		"[esif] initial_run: " + dir.file("nowhere") + ": run folder not found");
	// The header line and the first 150 of the run's 200 poses.
	const std::string tum = readText(dir.file("ekf/trajectory.tum"));
	std::size_t cut = 0;
	for (int line = 0; line < 151; ++line) cut = tum.find('\n', cut) + 1;
	fs::create_directory(dir.file("short"));
	std::ofstream(dir.file("short/trajectory.tum")) << tum.substr(0, cut);
	fs::copy_file(dir.file("ekf/landmarks.txt"), dir.file("short/landmarks.txt"));
	expectOneErrorLine(
		runEsif(run(config("CeresFullSlam", dir.file("short")), dir_->file("small.rawlog"), dir.file("out"))),
		"trajectory.tum: 150 poses, the rawlog has 200 steps");
	EXPECT_FALSE(fs::exists(dir.file("out")));
	const auto r = runEsif(run(config("CeresFullSlam", dir.file("ekf")), dir_->file("small.rawlog"), dir.file("out")));
	EXPECT_EQ(r.exit_code, 0) << r.out;
	EXPECT_NE(readText(dir.file("out/params.ini")).find("initial_run = " + dir.file("ekf")), std::string::npos);
}

TEST(SideInputCounts, DevicesAndCommandLineCountsAreBounded)
{
	TempDir dir;
	expectOneErrorLine(runEsif("import victoria-park --in /dev/zero --out " + quoted(dir.file("z.rawlog"))),
				  "/dev/zero: Victoria Park file is not a regular file");
	const std::string mc = "montecarlo --scenario " + quoted(sourcePath("configs/sim/small.ini")) + " --configs " +
						   quoted(kEkf) + " --out " + quoted(dir.file("mc"));
	expectOneErrorLine(runEsif(mc + " --runs 2147483647"), "--runs 2147483647: must be in [1, 100000]");
	expectOneErrorLine(runEsif(mc + " --runs 100000000 --emit-jobs " + quoted(dir.file("jobs.txt"))),
				  "--runs 100000000: must be in [1, 100000]");
	expectOneErrorLine(runEsif(mc + " --runs 2 --jobs 100000"), "--jobs 100000: must be in [1, 256]");
	expectOneErrorLine(runEsif("bench sparse --features 1000000000"), "--features: '1000000000' is not a whole number in [20, 20000]");
	expectOneErrorLine(runEsif("bench sparse --steps 1000000000"), "--steps: must be in [1, 100000]");
	EXPECT_FALSE(fs::exists(dir.file("mc")));
	EXPECT_FALSE(fs::exists(dir.file("jobs.txt")));
}

/// campaign.ini's runs used to wrap (4294967297 was read as 1).
TEST(SideInputCounts, CampaignRunsAreCheckedBeforeTheyBecomeInts)
{
	TempDir dir;
	fs::create_directory(dir.file("mc"));
	for (const std::string runs : {"99999999999", "4294967297", "100001", "0"})
	{
		std::ofstream(dir.file("mc/campaign.ini"))
			<< "[montecarlo]\nscenario = " << sourcePath("configs/sim/small.ini") << "\nseed0 = 1\nruns = " << runs
			<< "\nconfigs = " << kEkf << "\nnames = ekf\n";
		expectOneErrorLine(runEsif("montecarlo --collect " + quoted(dir.file("mc"))),
					  "campaign.ini: [montecarlo] runs: missing or outside [1, 100000]");
	}
}

/// A job killed while simulating leaves sim/.seed_S.partial-PID; the next
/// job that needs seed S removes it under the seed's lock (a resumed
/// campaign used to keep it forever).
TEST(SideInputCounts, ACampaignRemovesThePartialSimulationsOfKilledJobs)
{
	TempDir dir;
	const std::string mc = dir.file("mc");
	const std::string args = "montecarlo --scenario " + quoted(sourcePath("configs/sim/small.ini")) + " --configs " +
							 quoted(kEkf) + " --jobs 1 --out " + quoted(mc);
	ASSERT_EQ(runEsif(args + " --runs 1").exit_code, 0);
	fs::create_directories(mc + "/sim/.seed_0002.partial-999999");
	std::ofstream(mc + "/sim/.seed_0002.partial-999999/sim.rawlog") << "half";
	const auto r = runEsif(args + " --runs 2");
	EXPECT_EQ(r.exit_code, 0) << r.out;
	EXPECT_FALSE(fs::exists(mc + "/sim/.seed_0002.partial-999999"));
	EXPECT_TRUE(fs::exists(mc + "/sim/seed_0002/sim.rawlog"));
	for (const auto& entry : fs::directory_iterator(mc + "/sim"))
		EXPECT_EQ(entry.path().filename().string().rfind("seed_", 0), 0u) << "left behind: " << entry.path();
}

/// A loop of symbolic links is named as such (it used to end in an internal
/// error from std::filesystem), for local maps, links.txt and ground truth.
TEST_F(SideInputs, LoopsOfSymbolicLinksAreNamed)
{
	{
		TempDir dir;
		const std::string maps = mapsCopy(dir);
		fs::create_symlink("links.txt", maps + "/links.txt.tmp");
		fs::remove(maps + "/links.txt");
		fs::rename(maps + "/links.txt.tmp", maps + "/links.txt");  // links.txt -> links.txt
		expectOneErrorLine(runEsif(runOnMaps(maps, dir.file("out"))), "links.txt: local-map links is a loop of symbolic links");
		fs::remove(maps + "/links.txt");
		fs::remove(maps + "/localmap_2.txt");
		fs::create_symlink("localmap_2.txt", maps + "/localmap_2.txt");
		expectOneErrorLine(runEsif(runOnMaps(maps, dir.file("out"))), "localmap_2.txt: local map is a loop of symbolic links");
	}
	{
		TempDir dir;
		const std::string log = rawlogCopy(dir);
		fs::remove(dir.file("log_ground_truth.txt"));
		fs::create_symlink("log_ground_truth.txt", dir.file("log_ground_truth.txt"));
		expectOneErrorLine(runEsif(run(kEkf, log, dir.file("out"))),
					  "log_ground_truth.txt: ground-truth landmarks is a loop of symbolic links");
	}
}

// ------------------------------------------------------------ strict text

TEST_F(SideInputs, IniContinuationLinesAndNulBytesAreErrorsNamingTheLine)
{
	TempDir dir;
	std::ofstream(dir.file("cont.ini")) << "[esif]\nplugin = EkfSlam\nlabel = ekf \\\nhide_landmark_ids = true\n";
	expectOneErrorLine(runEsif(run(dir.file("cont.ini"), dir_->file("small.rawlog"), dir.file("out"))),
				  "cont.ini:3: ends in '\\', which MRPT's parser joins with the next line");
	std::ofstream(dir.file("nul.ini")) << "[esif]\nplugin = EkfSlam\n[ekf]\njacobians = first_estimates"
									   << std::string(1, '\0') << "\n";
	expectOneErrorLine(runEsif(run(dir.file("nul.ini"), dir_->file("small.rawlog"), dir.file("out"))),
				  "nul.ini:4: a NUL byte at column 28");
}

/// A scenario must be one: a misspelt section, another section, an empty
/// file or a filter config used to simulate the default world with exit 0.
TEST(SideInputScenario, AScenarioHasOnlyASimulationSection)
{
	TempDir dir;
	const std::string small = readText(sourcePath("configs/sim/small.ini"));
	std::ofstream(dir.file("typo.ini")) << "[simulatoin]\nsteps = 10\n";
	std::ofstream(dir.file("extra.ini")) << small << "\n[ekf]\nx = 1\n";
	std::ofstream(dir.file("empty.ini")) << "";
	const std::vector<std::pair<std::string, std::string>> cases = {
		{dir.file("typo.ini"), "typo.ini: [simulatoin]: unknown section (a scenario has only [simulation])"},
		{dir.file("extra.ini"), "extra.ini: [ekf]: unknown section"},
		{dir.file("empty.ini"), "empty.ini: no [simulation] section (not a scenario file)"},
		{kEkf, "ekf.ini: [ekf]: unknown section"}};
	for (const auto& [scenario, phrase] : cases)
	{
		expectOneErrorLine(runEsif("simulate --config " + quoted(scenario) + " --out " + quoted(dir.file("s.rawlog"))), phrase);
		expectOneErrorLine(runEsif("simulate --config " + quoted(scenario) + " --seed 3 --out " + quoted(dir.file("s.rawlog"))),
					  phrase);
		expectOneErrorLine(runEsif("montecarlo --scenario " + quoted(scenario) + " --configs " + quoted(kEkf) +
							  " --runs 1 --out " + quoted(dir.file("mc"))),
					  phrase);
	}
	EXPECT_FALSE(fs::exists(dir.file("s.rawlog")));
	EXPECT_FALSE(fs::exists(dir.file("mc")));
}

TEST_F(SideInputs, GroundTruthIsAFileWithFiniteBoundedValues)
{
	TempDir dir;
	const std::string log = rawlogCopy(dir);
	// A folder where the file belongs used to give null metrics without a word.
	fs::rename(dir.file("log_ground_truth.txt"), dir.file("lm.txt"));
	fs::create_directory(dir.file("log_ground_truth.txt"));
	expectOneErrorLine(runEsif(run(kEkf, log, dir.file("out"))), "log_ground_truth.txt: ground-truth landmarks is a folder, not a file");
	fs::remove(dir.file("log_ground_truth.txt"));
	fs::rename(dir.file("lm.txt"), dir.file("log_ground_truth.txt"));
	// A yaw of 1e300 used to be accepted (landmark RMSE 61.8 m for 0.064 m).
	std::ofstream(dir.file("log_ground_truth_robot_path.txt")) << "0 0 0 1e300 0 0\n";
	expectOneErrorLine(runEsif(run(kEkf, log, dir.file("out"))),
				  "log_ground_truth_robot_path.txt:1: column 4 (yaw) = 1e+300: must be within +-1e+06 rad");
}

TEST_F(SideInputs, LocalMapGroundTruthAndReferenceValuesAreBounded)
{
	TempDir dir;
	const std::string maps = mapsCopy(dir);
	const std::string truth = readText(maps + "/ground_truth_landmarks.txt");
	ASSERT_FALSE(truth.empty());
	std::ofstream(maps + "/ground_truth_landmarks.txt") << "1 1e9 0\n";
	expectOneErrorLine(runEsif(runOnMaps(maps, dir.file("out"))),
					   "ground_truth_landmarks.txt:1: column 2 (x) = 1e+09: must be within +-1e+07 m");
	std::ofstream(maps + "/ground_truth_landmarks.txt") << truth;
	std::ofstream(maps + "/ground_truth_end_poses.txt") << "1 0 0 1e300\n";
	expectOneErrorLine(runEsif(runOnMaps(maps, dir.file("out"))),
					   "ground_truth_end_poses.txt:1: column 4 (phi) = 1e+300: must be within +-1e+06 rad");
	fs::remove(maps + "/ground_truth_end_poses.txt");

	fs::create_directory(dir.file("ref"));
	std::ofstream(dir.file("ref/feature.txt")) << "1 1e300 0\n";
	expectOneErrorLine(runEsif(runOnMaps(maps, dir.file("out"), "--reference-result " + quoted(dir.file("ref")))),
				  "feature.txt:1: column 2 (x) = 1e+300: must be within +-1e+07 m");
}

/// A solver's output of another problem: no landmarks, shifted IDs or an
/// absurd position used to be read with exit 0.
TEST_F(SideInputs, ImportG2oChecksEveryLandmarkVertexAgainstTheRawlogsProblem)
{
	TempDir dir;
	const std::string log = dir_->file("small.rawlog"), g2o = dir.file("p.g2o");
	ASSERT_EQ(runEsif("export g2o --rawlog " + quoted(log) + " --out " + quoted(g2o)).exit_code, 0);
	const std::string text = readText(g2o);
	// Without the landmarks; with every landmark vertex (and its edges) 50,000
	// further on; with one landmark 10^18 m away.
	std::string poses_only, shifted, far;
	std::istringstream lines(text);
	long first_point = -1;
	for (std::string line; std::getline(lines, line);)
	{
		std::istringstream row(line);
		std::vector<std::string> t;
		for (std::string token; row >> token;) t.push_back(token);
		const bool point = !t.empty() && t[0] == "VERTEX_XY";
		const bool point_edge = !t.empty() && (t[0] == "EDGE_SE2_XY" || t[0] == "BR");
		if (point && first_point < 0) first_point = std::stol(t[1]);
		if (!point && !point_edge) poses_only += line + "\n";
		far += point && std::stol(t[1]) == first_point ? "VERTEX_XY " + t[1] + " 1e18 0\n" : line + "\n";
		if (point || point_edge)
		{
			const std::size_t id_at = point ? 1 : 2;
			t[id_at] = std::to_string(std::stol(t[id_at]) + 50000);
			for (const auto& token : t) shifted += token + " ";
			shifted += "\n";
		}
		else
			shifted += line + "\n";
	}
	ASSERT_GE(first_point, 0) << "the export has landmark vertices";
	const auto import = [&](const std::string& content) {
		std::ofstream(dir.file("solved.g2o")) << content;
		return runEsif("import g2o --g2o " + quoted(dir.file("solved.g2o")) + " --rawlog " + quoted(log) + " --out " +
					   quoted(dir.file("out")));
	};
	expectOneErrorLine(import(poses_only), "solved.g2o: no VERTEX_XY " + std::to_string(first_point));
	expectOneErrorLine(import(shifted), "which the rawlog's problem does not have");
	expectOneErrorLine(import(far), "'1e18' is beyond +-1e7 m");
	EXPECT_FALSE(fs::exists(dir.file("out")));
	const auto r = import(text);
	EXPECT_EQ(r.exit_code, 0) << r.out;
}

// ------------------------------------------------------------ command line

TEST(SideInputCommandLine, ErrorsExitOneAndShowTokensEscapedAndCut)
{
	const auto none = runEsif("");
	EXPECT_EQ(none.exit_code, 1) << none.out;
	// printf in the shell: the command line holds the raw bytes 0x01, 0x1b and 0x7f.
	const auto binary = runEsif("\"$(printf '\\001\\033[31mred\\177')\"");
	EXPECT_EQ(binary.exit_code, 1) << binary.out;
	EXPECT_NE(binary.out.find("unknown command '\\x01\\x1b[31mred\\x7f'"), std::string::npos) << binary.out;
	for (const char c : binary.out) EXPECT_FALSE(c != '\n' && static_cast<unsigned char>(c) < 0x20) << binary.out;
	const auto long_token = runEsif(std::string(300, 'a'));
	EXPECT_NE(long_token.out.find("'" + std::string(80, 'a') + "...'"), std::string::npos) << long_token.out;
	const auto bad_option = runEsif("run --config \"$(printf '\\002')\" --rawlog x --out y --frob \"$(printf '\\003')\"");
	EXPECT_EQ(bad_option.exit_code, 1) << bad_option.out;
	for (const char c : bad_option.out) EXPECT_FALSE(c != '\n' && static_cast<unsigned char>(c) < 0x20) << bad_option.out;
}

}  // namespace
