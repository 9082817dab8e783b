// Reusing one run's data association in another, as a user does it: every
// `esif run` writes associations.txt and the formulation in stats.json;
// `[esif] associations_from` (or `esif run --associations-from`) feeds those
// decisions as landmark IDs; `esif compare` runs the config named by label
// first and prints the book's Table 5.1 layout. Mistakes are one line.

#include <EsifTestSupport.h>

#include <esif/formats/AssociationFile.h>

#include <gtest/gtest.h>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

namespace
{
using esif::test::readText;
using esif::test::runEsif;
using esif::test::sourcePath;
using esif::test::TempDir;

/// Rows of an associations.txt (its comment header left out).
std::string rowsOf(const std::string& path)
{
	std::istringstream in(readText(path));
	std::string rows;
	for (std::string line; std::getline(in, line);)
		if (!line.empty() && line[0] != '#') rows += line + "\n";
	return rows;
}

std::size_t lineCount(const std::string& s) { return std::count(s.begin(), s.end(), '\n'); }

/// The small simulated rawlog; a JCBB EKF that associates on its own (IDs
/// hidden); an EKF using the rawlog's IDs, whose decisions are reused by
/// EKFs that can only use IDs but have the rawlog's hidden (known_ids
/// refuses a measurement without ID, so the source must reject none).
class AssociationsFrom : public ::testing::Test
{
   protected:
	static void SetUpTestSuite()
	{
		dir_ = std::make_unique<TempDir>();
		const auto r = esif::test::simulateSmall(dir_->file("small.rawlog"));
		ASSERT_EQ(r.exit_code, 0) << r.out;
		std::ofstream(dir_->file("jcbb.ini"))
			<< "[esif]\nplugin = EkfSlam\nlabel = jcbb\nhide_landmark_ids = true\n[ekf]\nassociation = jcbb\n";
		// The source run trusts the IDs (no ID gate): a measurement its gate
		// rejected would reach the replaying known_ids filter without an ID,
		// which it refuses (an open interplay of the gate and
		// associations_from).
		std::ofstream(dir_->file("ids.ini"))
			<< "[esif]\nplugin = EkfSlam\nlabel = ids\n[ekf]\nassociation = known_ids\nid_gate_chi2_quantile = 1\n";
		writeKnownIds("known.ini", "");
	}
	static void TearDownTestSuite() { dir_.reset(); }

	/// An EKF using IDs only, with the rawlog's hidden: it needs associations_from.
	/// Its ID gate is off like the source's, so that both make the same decisions.
	static std::string writeKnownIds(const std::string& name, const std::string& associations_from)
	{
		std::ofstream(dir_->file(name)) << "[esif]\nplugin = EkfSlam\nlabel = " << name.substr(0, name.find('.'))
										<< "\nhide_landmark_ids = true\n"
										<< (associations_from.empty() ? "" : "associations_from = " + associations_from + "\n")
										<< "[ekf]\nassociation = known_ids\nid_gate_chi2_quantile = 1\n";
		return dir_->file(name);
	}

	static std::string runArgs(const std::string& config, const std::string& out)
	{
		return "run -q --config '" + config + "' --rawlog '" + dir_->file("small.rawlog") + "' --out '" +
			   dir_->file(out) + "'";
	}

	static std::unique_ptr<TempDir> dir_;
};
std::unique_ptr<TempDir> AssociationsFrom::dir_;

TEST_F(AssociationsFrom, EveryRunWritesAssociationsAndFormulation)
{
	const auto r = runEsif(runArgs(dir_->file("jcbb.ini"), "jcbb_out"));
	ASSERT_EQ(r.exit_code, 0) << r.out;
	const auto stats = readText(dir_->file("jcbb_out/stats.json"));
	EXPECT_NE(stats.find("\"formulation\": \"ekf_slam\""), std::string::npos) << stats;
	EXPECT_NE(stats.find("\"poses_in_state\": 1"), std::string::npos) << stats;

	const auto recorded = esif::readAssociationFile(dir_->file("jcbb_out/associations.txt"), 200);
	EXPECT_EQ(recorded.steps.size(), 200u);
	std::size_t rows = 0;
	for (const auto& s : recorded.steps) rows += s.associations.size();
	EXPECT_NE(stats.find("\"measurements\": " + std::to_string(rows) + ","), std::string::npos) << rows << stats;
	EXPECT_GT(rows, 0u);
}

TEST_F(AssociationsFrom, KnownIdsFilterReplaysAnotherRunsAssociation)
{
	ASSERT_EQ(runEsif(runArgs(dir_->file("ids.ini"), "source")).exit_code, 0);
	const auto config = writeKnownIds("reuse.ini", dir_->file("source"));
	const auto r = runEsif(runArgs(config, "reuse"));
	ASSERT_EQ(r.exit_code, 0) << r.out;
	// Same decisions measurement by measurement: with the rawlog's IDs hidden, they came from the file.
	EXPECT_EQ(rowsOf(dir_->file("reuse/associations.txt")), rowsOf(dir_->file("source/associations.txt")));
	EXPECT_NE(readText(dir_->file("reuse/params.ini")).find("associations_from = " + dir_->file("source")),
			  std::string::npos);
	// Still scored against the rawlog's true IDs.
	const auto stats = readText(dir_->file("reuse/stats.json"));
	EXPECT_EQ(stats.find("\"da_wrong\": null"), std::string::npos) << stats;

	// The command-line option overrides the INI key.
	const auto cli = runEsif(runArgs(dir_->file("known.ini"), "reuse_cli") + " --associations-from '" +
							 dir_->file("source") + "'");
	ASSERT_EQ(cli.exit_code, 0) << cli.out;
	EXPECT_EQ(rowsOf(dir_->file("reuse_cli/associations.txt")), rowsOf(dir_->file("source/associations.txt")));
}

TEST_F(AssociationsFrom, MissingFolderIsOneLineBeforeAnyOutput)
{
	const auto config = writeKnownIds("missing.ini", dir_->file("nowhere"));
	const auto r = runEsif(runArgs(config, "missing_out"));
	EXPECT_EQ(r.exit_code, 1) << r.out;
	EXPECT_EQ(lineCount(r.out), 1u) << r.out;
	EXPECT_NE(r.out.find("esif: error: " + config + ": [esif] associations_from: " + dir_->file("nowhere") +
						 "/associations.txt not found (run that config first)"),
			  std::string::npos)
		<< r.out;
	EXPECT_FALSE(std::filesystem::exists(dir_->file("missing_out")));

	const auto cli = runEsif(runArgs(dir_->file("known.ini"), "missing_out") + " --associations-from '" +
							 dir_->file("nowhere") + "'");
	EXPECT_EQ(cli.exit_code, 1) << cli.out;
	EXPECT_NE(cli.out.find(": --associations-from: " + dir_->file("nowhere") + "/associations.txt not found"),
			  std::string::npos)
		<< cli.out;
}

TEST_F(AssociationsFrom, AssociationsOfAnotherRawlogAreRefused)
{
	ASSERT_EQ(runEsif(runArgs(dir_->file("ids.ini"), "for_other")).exit_code, 0);
	const auto other = esif::test::simulateSmall(dir_->file("other.rawlog"), "--seed 7");
	ASSERT_EQ(other.exit_code, 0) << other.out;
	const auto r = runEsif(
		"run -q --config '" + writeKnownIds("wrong.ini", dir_->file("for_other")) + "' --rawlog '" +
		dir_->file("other.rawlog") + "' --out '" + dir_->file("wrong_out") + "'");
	EXPECT_EQ(r.exit_code, 1) << r.out;
	EXPECT_EQ(lineCount(r.out), 1u) << r.out;
	EXPECT_NE(r.out.find("esif: error: " + dir_->file("for_other/associations.txt") + ": step "), std::string::npos)
		<< r.out;
	EXPECT_NE(r.out.find(" associations for "), std::string::npos) << r.out;
	EXPECT_FALSE(std::filesystem::exists(dir_->file("wrong_out")));
}

TEST_F(AssociationsFrom, CompareRunsTheNamedConfigFirstAndKeepsTheOrder)
{
	// The user of ids' association is listed first; ids must still run first.
	const auto user = writeKnownIds("user.ini", "ids");
	const auto r = runEsif(
		"compare --configs '" + user + "," + dir_->file("ids.ini") + "' --rawlog '" + dir_->file("small.rawlog") +
		"' --out '" + dir_->file("cmp") + "'");
	ASSERT_EQ(r.exit_code, 0) << r.out;
	const auto ids_at = r.out.find("esif compare: running " + dir_->file("ids.ini"));
	const auto user_at = r.out.find("esif compare: running " + user);
	ASSERT_NE(ids_at, std::string::npos) << r.out;
	ASSERT_NE(user_at, std::string::npos) << r.out;
	EXPECT_LT(ids_at, user_at) << r.out;
	EXPECT_EQ(rowsOf(dir_->file("cmp/user/associations.txt")), rowsOf(dir_->file("cmp/ids/associations.txt")));

	// Tables in the configs' order.
	const auto csv = readText(dir_->file("cmp/comparison.csv"));
	EXPECT_LT(csv.find("\nEkfSlam,ekf_slam,user,"), csv.find("\nEkfSlam,ekf_slam,ids,")) << csv;
	const auto run_row = r.out.find("\nrun ");
	ASSERT_NE(run_row, std::string::npos) << r.out;
	EXPECT_LT(r.out.find("user", run_row), r.out.find("ids", run_row)) << r.out;

	// Table 5.1 layout: no book estimator among two EKF runs, so every book column is "not available".
	const auto table = r.out.find("Table 5.1 layout: performance of exactly sparse information filters\n");
	ASSERT_NE(table, std::string::npos) << r.out;
	std::size_t at = table;
	for (const char* heading : {"full SLAM", "D-SLAM", "D-SLAM local map joining filter", "SLSJF", "user", "ids"})
	{
		at = r.out.find(heading, at);
		ASSERT_NE(at, std::string::npos) << heading << " in " << r.out.substr(table);
	}
	EXPECT_NE(r.out.find("Number of poses", table), std::string::npos) << r.out;
	const auto md = readText(dir_->file("cmp/comparison.md"));
	EXPECT_NE(md.find("## Table 5.1 layout"), std::string::npos) << md;
	EXPECT_NE(md.find("| Number of poses | not available | not available | not available | not available | 1 | 1 |"),
			  std::string::npos)
		<< md;
	// No full-SLAM run: no baseline columns.
	EXPECT_EQ(r.out.find("base_"), std::string::npos) << r.out;
}

TEST_F(AssociationsFrom, CompareRefusesSelfReferenceAndCyclesBeforeAnyRun)
{
	const auto self = writeKnownIds("self.ini", "self");
	auto r = runEsif(
		"compare --configs '" + self + "," + dir_->file("ids.ini") + "' --rawlog '" + dir_->file("small.rawlog") +
		"' --out '" + dir_->file("cmp_self") + "'");
	EXPECT_EQ(r.exit_code, 1) << r.out;
	EXPECT_EQ(lineCount(r.out), 1u) << r.out;
	EXPECT_NE(r.out.find("esif: error: " + self + ": [esif] associations_from = self: names this config's own label"),
			  std::string::npos)
		<< r.out;
	EXPECT_FALSE(std::filesystem::exists(dir_->file("cmp_self")));

	const auto a = writeKnownIds("ca.ini", "cb");
	const auto b = writeKnownIds("cb.ini", "ca");
	r = runEsif(
		"compare --configs '" + a + "," + b + "' --rawlog '" + dir_->file("small.rawlog") + "' --out '" +
		dir_->file("cmp_cycle") + "'");
	EXPECT_EQ(r.exit_code, 1) << r.out;
	EXPECT_EQ(lineCount(r.out), 1u) << r.out;
	EXPECT_NE(r.out.find("forms a cycle: " + a + " (ca) -> " + b + " (cb) -> " + a), std::string::npos) << r.out;
	EXPECT_FALSE(std::filesystem::exists(dir_->file("cmp_cycle")));
}

}  // namespace
