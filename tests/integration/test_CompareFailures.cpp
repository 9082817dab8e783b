// `esif compare` when runs fail: every config and plugin is checked before
// the first run, a failed run is a row of its own (status, exit code, first
// error line) while the others still run, the tables are always written,
// and compare exits with the child's code. Also the remark on an
// optimization baseline whose own check finds its optimum implausible.
// Failing and implausible runs come from test-only plugins
// (support/FailingFilter.cpp, support/ImplausibleOptimum.cpp) and from a
// real one made to fail (the Ceres full-SLAM baseline with IDs hidden).

#include <EsifTestSupport.h>

#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

namespace
{
using esif::test::readText;
using esif::test::runEsif;
using esif::test::TempDir;

class CompareFailures : public ::testing::Test
{
   protected:
	static void SetUpTestSuite()
	{
		dir_ = std::make_unique<TempDir>();
		const auto r = esif::test::simulateSmall(dir_->file("small.rawlog"));
		ASSERT_EQ(r.exit_code, 0) << r.out;
		std::ofstream(dir_->file("ekf.ini")) << "[esif]\nplugin = EkfSlam\nlabel = ekf\n";
		// Throws a NumericalError at step 5: esif run exits 3.
		std::ofstream(dir_->file("failing.ini"))
			<< "[esif]\nplugin = test::FailingFilter\nlabel = failing\n[failing]\nfail_at_step = 5\n";
		// The Ceres baseline needs IDs: with them hidden, esif run stops with a
		// config error (exit 1) after reading the rawlog.
		std::ofstream(dir_->file("full_noids.ini"))
			<< "[esif]\nplugin = CeresFullSlam\nlabel = full_noids\nhide_landmark_ids = true\n";
		std::ofstream(dir_->file("unknown.ini")) << "[esif]\nplugin = NoSuchPlugin\nlabel = unknown\n";
		std::ofstream(dir_->file("badkey.ini")) << "[esif]\nplugin = test::FailingFilter\n[failing]\nfail_at = 5\n";
		// Reuses the failing run's data association: cannot run without it.
		std::ofstream(dir_->file("dependent.ini"))
			<< "[esif]\nplugin = EkfSlam\nlabel = dependent\nhide_landmark_ids = true\nassociations_from = failing\n";
		std::ofstream(dir_->file("implausible.ini")) << "[esif]\nplugin = test::ImplausibleOptimum\nlabel = opt\n";
		std::ofstream(dir_->file("plausible.ini"))
			<< "[esif]\nplugin = test::ImplausibleOptimum\nlabel = opt\n[implausible]\nplausible = true\n";
	}
	static void TearDownTestSuite() { dir_.reset(); }

	static esif::test::CommandResult compare(const std::string& configs, const std::string& out)
	{
		std::string list;
		std::stringstream ss(configs);
		for (std::string c; std::getline(ss, c, ',');) list += (list.empty() ? "" : ",") + dir_->file(c);
		return runEsif(
			"compare --configs '" + list + "' --rawlog '" + dir_->file("small.rawlog") + "' --out '" +
			dir_->file(out) + "' --plugin-dir '" + ESIF_TEST_PLUGIN_DIR + "'");
	}

	static std::unique_ptr<TempDir> dir_;
};
std::unique_ptr<TempDir> CompareFailures::dir_;

/// The CSV row whose first cell (label) is `label`.
std::string csvRow(const std::string& csv, const std::string& label)
{
	std::istringstream in(csv);
	for (std::string line; std::getline(in, line);)
		if (line.rfind(label + ",", 0) == 0) return line;
	return "";
}

TEST_F(CompareFailures, AFailedRunIsARowTheOthersRunAndTheChildsCodeIsKept)
{
	// The failing run first: the EKF after it still runs.
	const auto r = compare("failing.ini,ekf.ini", "one");
	EXPECT_EQ(r.exit_code, 3) << r.out;
	EXPECT_NE(r.out.find("esif compare: running " + dir_->file("ekf.ini")), std::string::npos) << r.out;
	EXPECT_TRUE(std::filesystem::exists(dir_->file("one/ekf/stats.json")));

	const std::string error = "esif: numerical failure: " + dir_->file("small.rawlog") +
							  ": step 5: test::FailingFilter fails here on purpose (fail_at_step)";
	EXPECT_NE(r.out.find("run 'failing' failed (exit 3): " + error + "\n"), std::string::npos) << r.out;
	const auto md = readText(dir_->file("one/comparison.md"));
	EXPECT_NE(md.find("| status | failed | ok |"), std::string::npos) << md;
	EXPECT_NE(md.find("| exit_code | 3 | - |"), std::string::npos) << md;
	EXPECT_NE(md.find("run 'failing' failed (exit 3): " + error), std::string::npos) << md;
	// The EKF's figures are there; the failed run's are not.
	EXPECT_NE(md.find("| landmark_rmse_m | - | 0."), std::string::npos) << md;

	const auto csv = readText(dir_->file("one/comparison.csv"));
	const auto header = csv.substr(0, csv.find('\n'));
	EXPECT_NE(header.find("status,exit_code,error"), std::string::npos) << header;
	EXPECT_EQ(csvRow(csv, "failing").rfind("failing,test::FailingFilter,failed,3," + error, 0), 0u)
		<< csv;
	EXPECT_NE(csvRow(csv, "ekf").find(",ok,"), std::string::npos) << csv;
}

TEST_F(CompareFailures, SeveralFailuresExitWithTheFirstInConfigOrder)
{
	const auto a = compare("full_noids.ini,failing.ini,ekf.ini", "two_a");
	EXPECT_EQ(a.exit_code, 1) << a.out;
	EXPECT_NE(a.out.find("run 'full_noids' failed (exit 1): esif: error: "), std::string::npos) << a.out;
	EXPECT_NE(a.out.find("needs landmark IDs"), std::string::npos) << a.out;
	EXPECT_NE(a.out.find("run 'failing' failed (exit 3)"), std::string::npos) << a.out;
	// The full-SLAM run would have been the baseline.
	EXPECT_NE(a.out.find("no optimization baseline: the full-SLAM run 'full_noids' failed, so no base_* ratios"),
			  std::string::npos)
		<< a.out;
	EXPECT_TRUE(std::filesystem::exists(dir_->file("two_a/comparison.csv")));

	const auto b = compare("failing.ini,full_noids.ini,ekf.ini", "two_b");
	EXPECT_EQ(b.exit_code, 3) << b.out;
}

TEST_F(CompareFailures, ARunReusingAFailedRunsAssociationIsNotRun)
{
	const auto r = compare("dependent.ini,failing.ini,ekf.ini", "dep");
	EXPECT_EQ(r.exit_code, 3) << r.out;
	EXPECT_NE(r.out.find("run 'dependent' not run: its associations_from run 'failing' failed"), std::string::npos)
		<< r.out;
	const auto md = readText(dir_->file("dep/comparison.md"));
	EXPECT_NE(md.find("| status | not run | failed | ok |"), std::string::npos) << md;
}

TEST_F(CompareFailures, ConfigsAndPluginsAreCheckedBeforeTheFirstRun)
{
	const auto r = compare("ekf.ini,unknown.ini", "unknown_out");
	EXPECT_EQ(r.exit_code, 1) << r.out;
	EXPECT_NE(r.out.find("esif: error: " + dir_->file("unknown.ini") + ": unknown plugin 'NoSuchPlugin'"),
			  std::string::npos)
		<< r.out;
	EXPECT_EQ(r.out.find("esif compare: running"), std::string::npos) << "nothing runs\n" << r.out;
	EXPECT_FALSE(std::filesystem::exists(dir_->file("unknown_out")));

	// A plugin's own key is checked too.
	const auto k = compare("ekf.ini,badkey.ini", "badkey_out");
	EXPECT_EQ(k.exit_code, 1) << k.out;
	EXPECT_NE(k.out.find("fail_at"), std::string::npos) << k.out;
	EXPECT_EQ(k.out.find("esif compare: running"), std::string::npos) << k.out;
}

TEST_F(CompareFailures, AnImplausibleBaselineIsSaidSo)
{
	const auto r = compare("ekf.ini,implausible.ini", "implausible_out");
	ASSERT_EQ(r.exit_code, 0) << r.out;
	const std::string remark =
		"baseline 'opt' implausible: chi2/dof 7.1, 2 degenerate poses; ratios and differences against it are not "
		"trustworthy";
	EXPECT_NE(r.out.find("base_*: ratio to the optimization baseline 'opt'"), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("esif: warning: " + remark + "\n"), std::string::npos) << r.out;
	EXPECT_NE(readText(dir_->file("implausible_out/comparison.md")).find(remark + "\n"), std::string::npos);

	const auto ok = compare("ekf.ini,plausible.ini", "plausible_out");
	ASSERT_EQ(ok.exit_code, 0) << ok.out;
	EXPECT_NE(ok.out.find("base_*: ratio to the optimization baseline 'opt'"), std::string::npos) << ok.out;
	EXPECT_EQ(ok.out.find("implausible"), std::string::npos) << ok.out;
}

}  // namespace
