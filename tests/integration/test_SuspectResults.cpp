// No silent empty or degenerate result (SuspectResult.h): a run that maps no
// landmark, fuses no local map or rejects more than half of its measurements
// still exits 0 with every output, but says so in one warning line, in
// stats.json (suspect, suspect_reason), as the status "suspect" of its row in
// esif compare, and in a Monte Carlo summary.

#include <EsifTestSupport.h>

#include <esif/eval/MonteCarloTables.h>
#include <esif/eval/SuspectResult.h>
#include <esif/formats/StatsJson.h>

#include <gtest/gtest.h>

#include <fstream>

namespace
{
using namespace esif;
using test::quoted;
using test::runEsif;
using test::TempDir;

/// small.ini's world seen through a 1 cm sensor: 200 steps, no measurement.
std::string blindRawlog(const TempDir& dir)
{
	std::ofstream(dir.file("blind.ini")) << "[simulation]\nseed = 1\nworld_size_m = 10\nfeatures_per_side = 4\n"
											"steps = 200\nwaypoint_margin_m = 2\nsensor_max_range_m = 0.01\n";
	const auto r = runEsif("simulate --config " + quoted(dir.file("blind.ini")) + " --out " + quoted(dir.file("blind.rawlog")));
	EXPECT_EQ(r.exit_code, 0) << r.out;
	EXPECT_NE(r.out.find("0 measurements"), std::string::npos) << r.out;
	return dir.file("blind.rawlog");
}

TEST(SuspectResults, AFilterThatMapsNothingSaysSoAndComparePrintsSuspect)
{
	TempDir dir;
	const std::string rawlog = blindRawlog(dir);
	const auto run = runEsif("run -q --config " + quoted(test::sourcePath("configs/ekf.ini")) + " --rawlog " +
							 quoted(rawlog) + " --out " + quoted(dir.file("ekf")));
	EXPECT_EQ(run.exit_code, 0) << run.out;
	EXPECT_EQ(run.out, "esif: warning: suspect result: it mapped no landmark (stats.json suspect = 1; the outputs are "
					   "written, look before using them)\n");
	const Stats stats = Stats::load(dir.file("ekf/stats.json"));
	EXPECT_EQ(stats.number("suspect"), 1.0);
	EXPECT_EQ(stats.text("suspect_reason"), std::string("it mapped no landmark"));

	const auto cmp = runEsif("compare --configs " + quoted(test::sourcePath("configs/ekf.ini")) + " --rawlog " +
							 quoted(rawlog) + " --out " + quoted(dir.file("cmp")));
	EXPECT_EQ(cmp.exit_code, 0) << cmp.out;
	const std::string table = test::readText(dir.file("cmp/comparison.md"));
	EXPECT_NE(table.find("| status | suspect |"), std::string::npos) << table;
	EXPECT_NE(table.find("run 'ekf' is suspect: it mapped no landmark"), std::string::npos) << table;
}

TEST(SuspectResults, ANormalRunIsNotSuspect)
{
	TempDir dir;
	const auto run = runEsif("run -q --config " + quoted(test::sourcePath("configs/ekf.ini")) + " --rawlog " +
							 quoted(test::sourcePath("rawlogs/grid196.rawlog")) + " --out " + quoted(dir.file("ekf")));
	EXPECT_EQ(run.exit_code, 0) << run.out;
	EXPECT_EQ(run.out.find("suspect"), std::string::npos) << run.out;
	const Stats stats = Stats::load(dir.file("ekf/stats.json"));
	EXPECT_EQ(stats.number("suspect"), 0.0);
	EXPECT_TRUE(stats.get("suspect_reason").has_value());
	EXPECT_FALSE(stats.text("suspect_reason").has_value()) << "null";
}

TEST(SuspectResults, EachRuleNamesItsCounts)
{
	const auto reason = [](const std::vector<std::pair<std::string, double>>& values) {
		Stats s;
		for (const auto& [k, v] : values) s.set(k, StatValue(v));
		return suspectReason(s);
	};
	EXPECT_EQ(reason({{"landmarks", 0}}), std::string("it mapped no landmark"));
	EXPECT_EQ(reason({{"landmarks", 12}, {"local_maps", 2}, {"plugin_local_maps_fused", 0}}),
			  std::string("it fused no local map (of 2)"));
	EXPECT_EQ(reason({{"landmarks", 12}, {"da_new", 12}, {"da_matched", 30}, {"da_rejected", 43}}),
			  std::string("it rejected 43 of 85 measurements"));
	EXPECT_FALSE(reason({{"landmarks", 12}, {"da_new", 12}, {"da_matched", 30}, {"da_rejected", 42}})) << "half is not more";
	EXPECT_FALSE(reason({{"landmarks", 12}, {"plugin_local_maps_fused", 3}}));
}

TEST(SuspectResults, AMonteCarloSummaryListsSuspectRuns)
{
	CampaignGaps gaps;
	gaps.planned = 2;
	gaps.suspect = {"ekf/seed_0002: suspect: it mapped no landmark"};
	const std::string md = monteCarloSummaryMarkdown("t", {}, gaps);
	EXPECT_NE(md.find("## Suspect runs (aggregated)\n\n- ekf/seed_0002: suspect: it mapped no landmark\n"),
			  std::string::npos)
		<< md;
}

}  // namespace
