// `esif montecarlo` under faults: an error inside a job (a file where its run
// folder should be, no descriptor left) is that job's failure, never an
// abort; a full disk leaves the previous summary whole; a second campaign on
// one folder is refused at once; a damaged run is redone, not a block; a
// link inside the campaign folder is refused; a path no job line can carry
// is refused before anything is written. Each campaign is configs/sim/small.ini
// (200 steps) with the EKF, one to four runs.

#include <ChildProcess.h>
#include <EsifTestSupport.h>

#include <esif/core/Text.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/file.h>
#include <thread>
#include <fcntl.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace
{
using esif::test::expectOneErrorLine;
using esif::test::finish;
using esif::test::spawnEsif;
using esif::test::SpawnLimits;
using esif::test::quoted;
using esif::test::readText;
using esif::test::runEsif;
using esif::test::runShell;
using esif::test::sourcePath;
using esif::test::TempDir;

std::vector<std::string> campaignArgs(const std::string& out, int runs, const std::string& configs = "ekf.ini")
{
	std::string list;
	for (std::size_t at = 0; at < configs.size();)
	{
		const std::size_t end = std::min(configs.find(',', at), configs.size());
		list += (list.empty() ? "" : ",") + sourcePath("configs/" + configs.substr(at, end - at));
		at = end + 1;
	}
	return {"montecarlo", "--scenario", sourcePath("configs/sim/small.ini"), "--configs", list, "--runs",
			std::to_string(runs), "--out", out};
}

/// `word` single-quoted for the shell, its own quotes too.
std::string shellWord(const std::string& word) { return "'" + esif::replaceAll(word, "'", "'\\''") + "'"; }

std::string shellLine(const std::vector<std::string>& args)
{
	std::string line;
	for (const auto& a : args) line += (line.empty() ? "" : " ") + shellWord(a);
	return line;
}

esif::test::CommandResult campaign(const std::string& out, int runs, const std::string& extra = "")
{
	return runEsif(shellLine(campaignArgs(out, runs)) + (extra.empty() ? "" : " " + extra));
}

/// The last line of `text` that is not empty.
std::string lastLine(const std::string& text)
{
	std::string last;
	std::istringstream in(text);
	for (std::string line; std::getline(in, line);)
		if (!line.empty()) last = line;
	return last;
}

TEST(CampaignFaults, AnErrorInsideAJobIsItsFailureNotAnAbort)
{
	TempDir dir;
	const std::string mc = dir.file("mc");
	ASSERT_EQ(campaign(mc, 2).exit_code, 0);
	fs::remove_all(mc + "/runs/ekf");
	std::ofstream(mc + "/runs/ekf") << "x\n";  // a file where the runs' folder should be
	const auto r = campaign(mc, 3, "--jobs 1");
	EXPECT_EQ(r.exit_code, 1) << r.out;
	EXPECT_NE(r.out.find("esif montecarlo: ekf/seed_0001 failed (exit 1): esif: error: " + mc + "/runs/ekf"),
			  std::string::npos)
		<< r.out;
	EXPECT_EQ(lastLine(r.out).rfind("esif: error: " + mc + ": no finished run to aggregate (3 failed", 0), 0u) << r.out;
	EXPECT_TRUE(fs::exists(mc + "/failures/ekf/seed_0003.txt")) << "recorded like any failed run";

	// No descriptor left for the runs' pipes and locks: one error line, no abort.
	const std::string mc2 = dir.file("mc2");
	const auto [code, text] = finish(spawnEsif(campaignArgs(mc2, 4, "ekf.ini,dslam.ini"), SpawnLimits{{}, {}, rlim_t{10}}));
	EXPECT_EQ(code, 1) << text;
	EXPECT_NE(lastLine(text).rfind("esif: error: ", 0), std::string::npos) << text;
}

TEST(CampaignFaults, AFullDiskLeavesThePreviousSummaryWhole)
{
	TempDir dir;
	const std::string mc = dir.file("mc");
	ASSERT_EQ(campaign(mc, 3).exit_code, 0);
	const std::string csv = readText(mc + "/summary.csv"), html = readText(mc + "/summary.html");
	// Every file may grow to the size of the largest one the runs write, not
	// to that of summary.html with its three figures inlined: the fourth run
	// finishes, its summary cannot be written.
	std::uintmax_t largest_run_file = 0;
	for (const auto& e : fs::recursive_directory_iterator(mc + "/runs"))
		if (e.is_regular_file()) largest_run_file = std::max(largest_run_file, e.file_size());
	for (const auto& e : fs::recursive_directory_iterator(mc + "/sim"))
		if (e.is_regular_file()) largest_run_file = std::max(largest_run_file, e.file_size());
	ASSERT_GT(html.size(), largest_run_file + 1024);
	const auto [code, text] = finish(spawnEsif(campaignArgs(mc, 4), SpawnLimits{largest_run_file + 1024, {}, {}}));
	EXPECT_EQ(code, 1) << text;
	EXPECT_NE(lastLine(text).find(": cannot write"), std::string::npos) << text;
	EXPECT_EQ(readText(mc + "/summary.csv"), csv) << "summary.csv of 4 runs beside summary.html of 3";
	EXPECT_EQ(readText(mc + "/summary.html"), html);
	EXPECT_TRUE(fs::exists(mc + "/runs/ekf/seed_0004/stats.json"));
	// With room again, the summary is written for all four.
	ASSERT_EQ(campaign(mc, 4).exit_code, 0);
	EXPECT_NE(readText(mc + "/summary.csv"), csv);
}

/// The same on a real full disk: a 2 MB tmpfs (root only, as CI runs).
TEST(CampaignFaults, AFullTmpfsEndsInOneErrorLine)
{
	if (::geteuid() != 0) GTEST_SKIP() << "mounting a tmpfs needs root";
	TempDir dir;
	const std::string tiny = dir.file("tiny");
	fs::create_directory(tiny);
	if (runShell("mount -t tmpfs -o size=2M tmpfs " + quoted(tiny)).exit_code != 0)
		GTEST_SKIP() << "mount -t tmpfs refused here (a container without CAP_SYS_ADMIN)";
	const auto r = campaign(tiny + "/mc", 30);
	runShell("umount " + quoted(tiny));
	EXPECT_NE(r.exit_code, 0) << r.out;
	EXPECT_NE(r.exit_code, 134) << "SIGABRT: " << r.out;
	EXPECT_EQ(lastLine(r.out).rfind("esif: error: ", 0), 0u) << r.out;
}

TEST(CampaignFaults, ASecondCampaignOnOneFolderIsRefusedAtOnce)
{
	TempDir dir;
	const std::string mc = dir.file("mc");
	const auto first = spawnEsif(campaignArgs(mc, 4, "ekf.ini,dslam.ini"));
	// Wait until the first holds the campaign's lock.
	for (int i = 0; i < 200 && !fs::exists(dir.file(".mc.lock")); ++i)
		std::this_thread::sleep_for(std::chrono::milliseconds(20));
	const auto second = runEsif(shellLine(campaignArgs(mc, 4, "ekf.ini,dslam.ini")) + " --jobs 1");
	expectOneErrorLine(second, mc + ": another esif process is writing this campaign");
	const auto [code, text] = finish(first);
	EXPECT_EQ(code, 0) << text;
	EXPECT_FALSE(fs::exists(mc + "/failures")) << "no run recorded as failed";

	// A job a worker of a job list runs is left to it by another worker.
	const std::string lock = mc + "/runs/ekf/.seed_0001.job.lock";
	const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT, 0644);
	ASSERT_EQ(::flock(fd, LOCK_EX), 0);
	fs::remove_all(mc + "/runs/ekf/seed_0001");
	const auto busy = runEsif("montecarlo --out " + quoted(mc) + " --job ekf/seed_0001");
	::close(fd);
	EXPECT_EQ(busy.exit_code, 0) << busy.out;
	EXPECT_NE(busy.out.find("ekf/seed_0001: running in another esif process, left to it"), std::string::npos) << busy.out;
	EXPECT_FALSE(fs::exists(mc + "/failures/ekf/seed_0001.txt"));
}

TEST(CampaignFaults, ADamagedRunIsRedoneAndNeverAggregated)
{
	TempDir dir;
	const std::string mc = dir.file("mc");
	ASSERT_EQ(campaign(mc, 3).exit_code, 0);
	fs::resize_file(mc + "/runs/ekf/seed_0002/stats.json", 100);
	// --collect lists it and aggregates the others.
	const auto collected = runEsif("montecarlo --collect " + quoted(mc));
	EXPECT_EQ(collected.exit_code, 0) << collected.out;
	EXPECT_NE(collected.out.find("2 of 3 runs finished"), std::string::npos) << collected.out;
	EXPECT_NE(readText(mc + "/summary.md").find("ekf/seed_0002: damaged, redone by the next run of the campaign: " + mc +
												"/runs/ekf/seed_0002/stats.json: malformed"),
			  std::string::npos)
		<< readText(mc + "/summary.md");
	// The resume redoes it.
	const auto resumed = campaign(mc, 3);
	EXPECT_EQ(resumed.exit_code, 0) << resumed.out;
	EXPECT_NE(resumed.out.find("3 of 3 runs finished"), std::string::npos) << resumed.out;

	// A NaN in a finished run's errors is damage too, never "nan" in the summary.
	const std::string errors = mc + "/runs/ekf/seed_0002/pose_errors.csv";
	std::string text = readText(errors);
	const auto row = text.find('\n', text.find('\n', text.find('\n') + 1) + 1) + 1;	 // the third data row
	text.replace(text.find(',', row) + 1, text.find(',', text.find(',', row) + 1) - text.find(',', row) - 1, "nan");
	std::ofstream(errors, std::ios::trunc) << text;
	const auto with_nan = runEsif("montecarlo --collect " + quoted(mc));
	EXPECT_EQ(with_nan.exit_code, 0) << with_nan.out;
	EXPECT_EQ(readText(mc + "/summary.csv").find("nan"), std::string::npos) << readText(mc + "/summary.csv");
	EXPECT_NE(readText(mc + "/summary.md").find("pose_errors.csv:4: error 'nan' is not finite"), std::string::npos)
		<< readText(mc + "/summary.md");
}

TEST(CampaignFaults, ALinkInsideTheCampaignIsRefusedAndNothingIsWrittenThroughIt)
{
	TempDir dir;
	const std::string mc = dir.file("mc");
	ASSERT_EQ(campaign(mc, 1).exit_code, 0);
	fs::create_directory(dir.file("elsewhere"));
	fs::rename(mc + "/runs/ekf", dir.file("elsewhere/ekf"));
	fs::create_directory_symlink(dir.file("elsewhere/ekf"), mc + "/runs/ekf");
	expectOneErrorLine(campaign(mc, 2), mc + "/runs/ekf: a symbolic link inside the campaign folder");
	EXPECT_FALSE(fs::exists(dir.file("elsewhere/ekf/seed_0002")));
	expectOneErrorLine(runEsif("montecarlo --collect " + quoted(mc)), "a symbolic link inside the campaign folder");
	expectOneErrorLine(runEsif("montecarlo --out " + quoted(mc) + " --job ekf/seed_0001"),
					   "a symbolic link inside the campaign folder");
}

TEST(CampaignFaults, APathNoJobLineCanCarryIsRefusedBeforeAnythingIsWritten)
{
	TempDir dir;
	// A newline in --out would end the job line: the engines would run the rest as a command.
	const std::string out = dir.file("camp") + "\n" + "touch " + dir.file("PWNED") + "\n";
	const auto [code, text] = finish(spawnEsif(
		{"montecarlo", "--scenario", sourcePath("configs/sim/small.ini"), "--configs", sourcePath("configs/ekf.ini"),
		 "--runs", "1", "--out", out, "--emit-jobs", dir.file("jobs.txt")}));
	EXPECT_EQ(code, 1) << text;
	EXPECT_NE(text.find("holds a line break or another control character: a job line cannot carry it"),
			  std::string::npos)
		<< text;
	EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
	EXPECT_TRUE(fs::is_empty(dir.path())) << "nothing written, not even the campaign's parent folder";

	// campaign.ini holds one config path per line: one with a newline is refused.
	const std::string config = dir.file("n\nx\n.ini");
	fs::copy_file(sourcePath("configs/ekf.ini"), config);
	const auto [config_code, config_text] = finish(spawnEsif(
		{"montecarlo", "--scenario", sourcePath("configs/sim/small.ini"), "--configs", config, "--runs", "1", "--out",
		 dir.file("c2")}));
	EXPECT_EQ(config_code, 1) << config_text;
	EXPECT_NE(config_text.find("a campaign cannot record a path with a line break"), std::string::npos) << config_text;
	EXPECT_FALSE(fs::exists(dir.file("c2")));

	// Quotes, $(), backticks and spaces are quoted, and a job line runs as one command.
	const std::string odd = dir.file("a 'b' $(touch x) `y`; z");
	ASSERT_EQ(campaign(odd, 1, "--emit-jobs " + shellWord(dir.file("ok.txt"))).exit_code, 0);
	const auto ran = runShell("cd " + quoted(dir.path()) + " && xargs -d '\\n' -n 1 sh -c < ok.txt");
	EXPECT_EQ(ran.exit_code, 0) << ran.out;
	EXPECT_TRUE(fs::exists(odd + "/runs/ekf/seed_0001/stats.json"));
	EXPECT_FALSE(fs::exists(dir.file("x")));
}

}  // namespace
