// Single-file outputs (simulate and import with the ground truth beside the
// rawlog, export g2o, montecarlo --emit-jobs) replace only what esif wrote
// as that kind of output, never an input, a campaign's own file or a
// user's; and the rawlog and its ground truth are committed together, so a
// kill at any moment leaves either the old set, the new set, or a set every
// reader refuses until it is written again (FileSet.h).

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
using esif::test::runShell;
using esif::test::simulateSmall;
using esif::test::sourcePath;
using esif::test::TempDir;

void put(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

/// A few lines in the Victoria Park format: four poses, two landmarks.
std::string tinyVictoriaPark()
{
	return "ODOMETRY 0 1 1.0 0 0 0.01 0 0 0.01 0 0.001\n"
		   "LANDMARK 1 7 5.0 1.0 0.4 0 0.4\n"
		   "ODOMETRY 1 2 1.0 0 0 0.01 0 0 0.01 0 0.001\n"
		   "LANDMARK 2 7 4.0 1.0 0.4 0 0.4\n"
		   "LANDMARK 2 8 3.0 -2.0 0.4 0 0.4\n"
		   "ODOMETRY 2 3 1.0 0 0 0.01 0 0 0.01 0 0.001\n";
}

TEST(OutputFiles, SimulateAndImportReplaceOnlyTheRawlogAndTruthEsifWrote)
{
	TempDir dir;
	const std::string rawlog = dir.file("e.rawlog"), truth = dir.file("e_ground_truth.txt");
	// The user's file at the name of the ground truth: refused, kept, nothing written.
	put(truth, "user notes\n");
	expectOneErrorLine(simulateSmall(rawlog), truth + ": exists and is not a file esif wrote");
	EXPECT_EQ(readText(truth), "user notes\n");
	EXPECT_FALSE(fs::exists(rawlog));
	// ... nor at the rawlog's own name.
	fs::remove(truth);
	put(rawlog, "my rawlog\n");
	expectOneErrorLine(simulateSmall(rawlog), rawlog + ": exists and is not a file esif wrote");
	EXPECT_EQ(readText(rawlog), "my rawlog\n");
	fs::remove(rawlog);

	// esif's own set is replaced, by simulate or import alike.
	ASSERT_EQ(simulateSmall(rawlog).exit_code, 0);
	const auto again = simulateSmall(rawlog, "--seed 2");
	ASSERT_EQ(again.exit_code, 0) << again.out;
	put(dir.file("vp.txt"), tinyVictoriaPark());
	const auto import = runEsif("import victoria-park --in " + quoted(dir.file("vp.txt")) + " --out " + quoted(rawlog));
	ASSERT_EQ(import.exit_code, 0) << import.out;
	// The simulation's ground truth went with it: the imported rawlog is never scored against it.
	EXPECT_FALSE(fs::exists(truth));
	EXPECT_FALSE(fs::exists(dir.file("e_ground_truth_robot_path.txt")));
	// Nothing left beside them but the record.
	for (const auto& e : fs::directory_iterator(dir.path()))
	{
		const std::string name = e.path().filename().string();
		EXPECT_TRUE(name == "e.rawlog" || name == ".e.rawlog.esif-files" || name == "vp.txt") << name;
	}

	// Changed by the user after esif wrote it: the user's now.
	ASSERT_EQ(simulateSmall(rawlog).exit_code, 0);
	put(truth, readText(truth) + " 1.0 2.0 0.0 5 0 0.0 99\n");
	expectOneErrorLine(simulateSmall(rawlog), truth + ": exists and was changed after esif wrote it");
}

TEST(OutputFiles, ExportG2oReplacesOnlyAG2oFileEsifWrote)
{
	TempDir dir;
	ASSERT_EQ(simulateSmall(dir.file("s.rawlog")).exit_code, 0);
	const auto exportTo = [&](const std::string& out) {
		return runEsif("export g2o --rawlog " + quoted(dir.file("s.rawlog")) + " --out " + quoted(out));
	};
	put(dir.file("x.g2o"), "user notes\n");
	expectOneErrorLine(exportTo(dir.file("x.g2o")), dir.file("x.g2o") + ": exists and is not a file esif wrote");
	EXPECT_EQ(readText(dir.file("x.g2o")), "user notes\n");
	ASSERT_EQ(exportTo(dir.file("y.g2o")).exit_code, 0);
	const auto again = exportTo(dir.file("y.g2o"));
	EXPECT_EQ(again.exit_code, 0) << again.out;
	// A rawlog esif wrote is another kind of output: not replaced by a g2o file.
	expectOneErrorLine(exportTo(dir.file("s.rawlog")), "is the rawlog");
	expectOneErrorLine(exportTo(dir.file("s_ground_truth.txt")), "is not a file esif wrote as a g2o file");
}

TEST(OutputFiles, AJobListIsNeverWrittenIntoACampaignNorOverAnotherKindOfFile)
{
	TempDir dir;
	const std::string mc = dir.file("mc");
	const std::string campaign = "montecarlo --scenario " + quoted(sourcePath("configs/sim/small.ini")) +
								 " --configs " + quoted(sourcePath("configs/ekf.ini")) + " --out " + quoted(mc);
	ASSERT_EQ(runEsif(campaign + " --runs 1").exit_code, 0);
	const std::string manifest = readText(mc + "/campaign.ini");
	const std::string stats = readText(mc + "/runs/ekf/seed_0001/stats.json");
	for (const std::string& inside : {mc + "/campaign.ini", mc + "/runs/ekf/seed_0001/stats.json", mc + "/jobs.txt"})
		expectOneErrorLine(runEsif(campaign + " --runs 2 --emit-jobs " + quoted(inside)), "lies inside the campaign folder");
	EXPECT_EQ(readText(mc + "/campaign.ini"), manifest);
	EXPECT_EQ(readText(mc + "/runs/ekf/seed_0001/stats.json"), stats);
	// Another campaign's summary, a user's file: not job lists esif wrote.
	const std::string other = dir.file("other");
	ASSERT_EQ(runEsif(campaign.substr(0, campaign.find(" --out ")) + " --out " + quoted(other) + " --runs 1").exit_code, 0);
	const std::string summary = readText(other + "/summary.csv");
	expectOneErrorLine(runEsif(campaign + " --runs 2 --emit-jobs " + quoted(other + "/summary.csv")),
					   other + "/summary.csv: exists and is not a file esif wrote as a job list");
	EXPECT_EQ(readText(other + "/summary.csv"), summary);
	// Its own job list is replaced.
	const std::string jobs = dir.file("jobs.txt");
	ASSERT_EQ(runEsif(campaign + " --runs 2 --emit-jobs " + quoted(jobs)).exit_code, 0);
	const auto again = runEsif(campaign + " --runs 3 --emit-jobs " + quoted(jobs));
	EXPECT_EQ(again.exit_code, 0) << again.out;
	const std::string lines = readText(jobs);
	EXPECT_EQ(std::count(lines.begin(), lines.end(), '\n'), 2) << lines;
	EXPECT_EQ(runEsif("montecarlo --collect " + quoted(mc)).exit_code, 0);
}

/// strace kills `esif simulate` at its Nth rename: every rename it makes,
/// writing the new set into its partial folder and committing it, is a
/// moment a SIGKILL can come. After each, the rawlog beside its truth is
/// either the old pair or the new one, or `esif run` refuses it; the next
/// simulate finishes or replaces the set and leaves nothing else behind.
TEST(OutputFiles, AKillAtAnyRenameNeverLeavesARawlogBesideAnotherOnesTruth)
{
	if (runShell("strace -V").exit_code != 0) GTEST_SKIP() << "strace not installed (.ci/run installs it)";
	TempDir dir;
	const std::string rawlog = dir.file("t.rawlog"), seed3 = dir.file("s3.rawlog");
	ASSERT_EQ(simulateSmall(seed3, "--seed 3").exit_code, 0);
	const auto isSeed3 = [&](const std::string& suffix) {
		return readText(dir.file("t" + suffix)) == readText(dir.file("s3" + suffix));
	};
	bool finished = false;
	for (int when = 1; !finished && when < 20; ++when)
	{
		ASSERT_EQ(simulateSmall(rawlog, "--seed 1").exit_code, 0);
		const auto killed = runShell(
			"strace -f -o /dev/null -e trace=rename -e inject=rename:signal=KILL:when=" + std::to_string(when) + " " +
			quoted(ESIF_BINARY) + " simulate --config " + quoted(sourcePath("configs/sim/small.ini")) +
			" --seed 3 --out " + quoted(rawlog));
		if (killed.out.find("Operation not permitted") != std::string::npos)
			GTEST_SKIP() << "strace cannot trace here: " << killed.out;
		finished = killed.exit_code == 0;  // past the last rename: nothing left to kill
		const bool new_rawlog = isSeed3(".rawlog"), new_truth = isSeed3("_ground_truth_robot_path.txt");
		const auto run = runEsif(
			"run -q --no-figures --config " + quoted(sourcePath("configs/ekf.ini")) + " --rawlog " + quoted(rawlog) +
			" --out " + quoted(dir.file("r" + std::to_string(when))));
		if (new_rawlog != new_truth)
		{
			expectOneErrorLine(run, rawlog + ": esif was stopped while replacing it");
		}
		else if (run.exit_code != 0)  // a whole pair, but the commit not yet marked complete
		{
			EXPECT_NE(run.out.find("esif was stopped while replacing it"), std::string::npos) << when << run.out;
		}
		// The next writer finishes what the kill left and takes the set over.
		const auto next = simulateSmall(rawlog, "--seed 3");
		ASSERT_EQ(next.exit_code, 0) << "after a kill at rename " << when << ": " << next.out;
		EXPECT_TRUE(isSeed3(".rawlog") && isSeed3("_ground_truth.txt") && isSeed3("_ground_truth_robot_path.txt"));
		for (const auto& e : fs::directory_iterator(dir.path()))
			EXPECT_EQ(e.path().filename().string().find(".partial-"), std::string::npos) << e.path();
	}
	EXPECT_TRUE(finished) << "the simulation makes fewer than 20 renames";
}

}  // namespace
