// Every kind of bad input reaches the user as one clear line naming the
// file, key or step, with a non-zero exit, and leaves no half-written output.

#include <EsifTestSupport.h>
#include <LocalMapTestSupport.h>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/serialization/CArchive.h>

#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>
#include <optional>

namespace
{
using esif::test::expectOneErrorLine;
using esif::test::runEsif;
using esif::test::sourcePath;
using esif::test::TempDir;

const std::string kRawlog = sourcePath("rawlogs/grid196.rawlog");
const std::string kConfig = sourcePath("configs/ekf.ini");

std::string writeConfig(const TempDir& dir, const std::string& text)
{
	const auto path = dir.file("c.ini");
	std::ofstream(path) << text;
	return path;
}

std::string runArgs(const std::string& config, const std::string& rawlog, const std::string& out)
{
	return "run -q --config '" + config + "' --rawlog '" + rawlog + "' --out '" + out + "'";
}

TEST(BadInput, MissingRawlog)
{
	TempDir dir;
	expectOneErrorLine(runEsif(runArgs(kConfig, dir.file("nope.rawlog"), dir.file("out"))), "nope.rawlog: rawlog file not found");
	EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

TEST(BadInput, UnreadableRawlog)
{
	TempDir dir;
	std::filesystem::create_directory(dir.file("folder"));
	expectOneErrorLine(runEsif(runArgs(kConfig, dir.file("folder"), dir.file("out"))), "rawlog file is a folder, not a file");
	if (::geteuid() == 0) GTEST_SKIP() << "root reads files whatever their mode";
	std::filesystem::copy_file(kRawlog, dir.file("locked.rawlog"));
	std::filesystem::permissions(dir.file("locked.rawlog"), std::filesystem::perms::none);
	expectOneErrorLine(runEsif(runArgs(kConfig, dir.file("locked.rawlog"), dir.file("out"))), "locked.rawlog");
}

TEST(BadInput, NotARawlog)
{
	TempDir dir;
	std::ofstream(dir.file("text.rawlog")) << "hello\n";
	expectOneErrorLine(runEsif(runArgs(kConfig, dir.file("text.rawlog"), dir.file("out"))), "not an MRPT rawlog");
}

TEST(BadInput, TruncatedRawlogIsProcessedWithAWarning)
{
	TempDir dir;
	// Decompress the demo, cut it inside an entry about two thirds in.
	const auto plain = dir.file("cut.rawlog");
	{
		mrpt::io::CFileGZInputStream in(kRawlog);
		mrpt::io::CFileOutputStream out(plain);
		char buf[65536];
		for (std::size_t n; (n = in.Read(buf, sizeof(buf))) > 0;) out.Write(buf, n);
	}
	std::filesystem::resize_file(plain, std::filesystem::file_size(plain) * 2 / 3 + 13);
	const auto r = runEsif(runArgs(kConfig, plain, dir.file("out")));
	EXPECT_EQ(r.exit_code, 0) << r.out;
	EXPECT_NE(r.out.find("esif: warning: "), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("read up to step"), std::string::npos) << r.out;
	for (const char* f : {"map.simplemap", "landmarks.gz", "landmarks.txt", "trajectory.tum", "scene.3Dscene",
						  "map.png", "stats.json"})
		EXPECT_TRUE(std::filesystem::exists(dir.file(std::string("out/") + f))) << f;
}

/// grid196.rawlog copied into `dir` with its landmark ground truth and the
/// first `path_rows` rows of its robot path (none: no path file).
std::string grid196With(const TempDir& dir, std::optional<std::size_t> path_rows)
{
	const auto log = dir.file("g.rawlog");
	std::filesystem::copy_file(kRawlog, log);
	std::filesystem::copy_file(sourcePath("rawlogs/grid196_ground_truth.txt"), dir.file("g_ground_truth.txt"));
	if (path_rows)
	{
		std::ifstream in(sourcePath("rawlogs/grid196_ground_truth_robot_path.txt"));
		std::ofstream out(dir.file("g_ground_truth_robot_path.txt"));
		std::size_t kept = 0;
		for (std::string line; std::getline(in, line) && kept < *path_rows;)
		{
			out << line << "\n";
			kept += !line.empty() && line[0] != '%';
		}
	}
	return log;
}

TEST(BadInput, GroundTruthInAnUnknownFrameOrOfTheWrongLengthGivesNullMetricsAndAWarning)
{
	// Without a robot path the landmarks cannot be put in the initial-pose
	// frame (the RMSE was 5.96 m instead of 0.090); a path that does not have
	// one pose per step pairs poses with the wrong steps.
	for (const std::optional<std::size_t> rows : {std::optional<std::size_t>(), std::optional<std::size_t>(1500)})
	{
		TempDir dir;
		const auto r = runEsif(runArgs(kConfig, grid196With(dir, rows), dir.file("out")));
		ASSERT_EQ(r.exit_code, 0) << r.out;
		EXPECT_NE(r.out.find(rows ? "1500 poses for 3000 steps" : "no robot-path ground truth"), std::string::npos)
			<< r.out;
		const auto stats = esif::test::readStatsJson(dir.file("out"));
		EXPECT_FALSE(stats.number("landmark_rmse_m")) << r.out;
		EXPECT_FALSE(stats.number("ate_rmse_m")) << r.out;
	}
	TempDir dir;  // the whole path: scored
	const auto r = runEsif(runArgs(kConfig, grid196With(dir, 1u << 20), dir.file("out")));
	ASSERT_EQ(r.exit_code, 0) << r.out;
	EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
	EXPECT_LT(*esif::test::readStatsJson(dir.file("out")).number("landmark_rmse_m"), 0.2);
}

TEST(BadInput, UnknownPlugin)
{
	TempDir dir;
	const auto cfg = writeConfig(dir, "[esif]\nplugin = NoSuchFilter\n");
	const auto r = runEsif(runArgs(cfg, kRawlog, dir.file("out")));
	expectOneErrorLine(r, "unknown plugin 'NoSuchFilter' (available: ");
	// Every plugin built is listed, whatever others join them.
	for (const char* plugin : {"Dslam", "EkfSlam"}) EXPECT_NE(r.out.find(plugin), std::string::npos) << r.out;
}

TEST(BadInput, MissingRequiredKey)
{
	TempDir dir;
	const auto cfg = writeConfig(dir, "[esif]\nlabel = x\n");
	expectOneErrorLine(runEsif(runArgs(cfg, kRawlog, dir.file("out"))), "[esif] plugin: missing");
}

TEST(BadInput, OutOfRangeParameter)
{
	TempDir dir;
	const auto cfg = writeConfig(dir, "[esif]\nplugin = EkfSlam\n[ekf]\ngate_chi2_quantile = 1.5\n");
	expectOneErrorLine(runEsif(runArgs(cfg, kRawlog, dir.file("out"))), "[ekf] gate_chi2_quantile = 1.5: must be in (0, 1)");
}

TEST(BadInput, MisspeltKeyAndUnknownSection)
{
	TempDir dir;
	auto cfg = writeConfig(dir, "[esif]\nplugin = EkfSlam\n[ekf]\ngate_chi2_quantil = 0.9\n");
	expectOneErrorLine(runEsif(runArgs(cfg, kRawlog, dir.file("out"))), "[ekf] gate_chi2_quantil: unknown key");
	cfg = writeConfig(dir, "[esif]\nplugin = EkfSlam\n[ekff]\n");
	expectOneErrorLine(runEsif(runArgs(cfg, kRawlog, dir.file("out"))), "[ekff]: unknown section");
}

TEST(BadInput, MissingConfigAndBadCommandLine)
{
	TempDir dir;
	expectOneErrorLine(runEsif(runArgs(dir.file("none.ini"), kRawlog, dir.file("out"))), "none.ini: config file not found");
	expectOneErrorLine(runEsif("run --rawlog x"), "esif run: ");
	expectOneErrorLine(runEsif("frobnicate"), "unknown command 'frobnicate' (usage: esif <command>");
	EXPECT_EQ(runEsif("frobnicate").exit_code, 1) << "a command-line error";
	expectOneErrorLine(runEsif(""), "no command given (usage: esif <command>");
	EXPECT_EQ(runEsif("").exit_code, 1);
}

TEST(BadInput, KnownIdsWithoutIdsNamesTheStep)
{
	TempDir dir;
	const auto cfg = writeConfig(dir, "[esif]\nplugin = EkfSlam\nhide_landmark_ids = true\n[ekf]\nassociation = known_ids\n");
	expectOneErrorLine(runEsif(runArgs(cfg, kRawlog, dir.file("out"))), "step 0, measurement 0: no landmark ID");
}

TEST(Cli, EverySubcommandHasHelp)
{
	for (const char* c : {"run", "compare", "simulate", "plugins"})
	{
		const auto r = runEsif(std::string(c) + " --help");
		EXPECT_EQ(r.exit_code, 0) << c;
		EXPECT_NE(r.out.find("USAGE"), std::string::npos) << c;
	}
}

TEST(Cli, PluginsListsEkfWithDefaults)
{
	const auto r = runEsif("plugins");
	EXPECT_EQ(r.exit_code, 0);
	EXPECT_NE(r.out.find("EkfSlam"), std::string::npos);
	EXPECT_NE(r.out.find("gate_chi2_quantile = 0.99"), std::string::npos);
}

TEST(Cli, PluginsListsTheHostKeysWithDefaults)
{
	const auto r = runEsif("plugins");
	EXPECT_EQ(r.exit_code, 0);
	const auto host = r.out.find("[esif]");
	ASSERT_NE(host, std::string::npos);
	// Before any plugin: the host's section is listed first.
	EXPECT_LT(host, r.out.find("EkfSlam"));
	for (const char* key : {"plugin = ", "label = ", "hide_landmark_ids = false", "keyframe_min_distance_m = 0",
							"image_size_px = 1000", "max_measurements_per_scan = 1000", "associations_from = ",
							"calibration = "})
		EXPECT_NE(r.out.find(std::string("\n  ") + key, host), std::string::npos) << key;
}

}  // namespace
