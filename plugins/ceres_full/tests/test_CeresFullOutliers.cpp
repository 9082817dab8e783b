// The baseline's outlier procedure ([ceres_full] outliers = drop, the
// default): on a simulated log with 1% misread IDs it drops the misreads,
// and only them (the simulator's measurement truth says which they are), and
// reaches the optimum of the clean problem; on a clean log it drops nothing
// and keeps the plain optimum of eq. 1.21.

#include <EsifTestSupport.h>

#include <esif/formats/AssociationFile.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/formats/StatsJson.h>
#include <esif/formats/MeasurementTruth.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace
{
using namespace esif;

Stats runAndReadStats(const std::string& config_text, const std::string& rawlog, const std::string& out,
					  const test::TempDir& dir)
{
	const std::string config = out + ".ini";
	std::ofstream(config) << config_text;
	const auto r = test::runEsif("run -q --config " + test::quoted(config) + " --rawlog " + test::quoted(rawlog) +
								 " --out " + test::quoted(out));
	EXPECT_EQ(r.exit_code, 0) << r.out;
	return Stats::load(out + "/stats.json");
}

using MeasurementKey = std::pair<std::size_t, std::size_t>;	 // step, measurement

/// The measurements a run's associations.txt rejected.
std::set<MeasurementKey> rejectedBy(const std::string& run, std::size_t steps)
{
	const RecordedAssociations recorded = readAssociationFile(run + "/associations.txt", steps);
	std::set<MeasurementKey> out;
	for (std::size_t k = 0; k < recorded.steps.size(); ++k)
		for (std::size_t j = 0; j < recorded.steps[k].associations.size(); ++j)
			if (recorded.steps[k].associations[j].kind == Association::Kind::Rejected) out.insert({k, j});
	return out;
}

/// Largest distance between the same landmark of two runs [m].
double largestLandmarkDifference(const std::string& a, const std::string& b)
{
	std::map<LandmarkId, Eigen::Vector2d> first;
	for (const auto& l : readLandmarksTxt(a + "/landmarks.txt")) first[l.id] = l.mean;
	double worst = 0;
	std::size_t matched = 0;
	for (const auto& l : readLandmarksTxt(b + "/landmarks.txt"))
		if (const auto it = first.find(l.id); it != first.end())
		{
			worst = std::max(worst, (it->second - l.mean).norm());
			++matched;
		}
	EXPECT_EQ(matched, first.size());
	return worst;
}

TEST(CeresFullOutliers, DropsTheMisreadIdsAndOnlyThemAndReachesTheCleanOptimum)
{
	test::TempDir dir;
	const std::string rawlog = dir.file("wrong_ids.rawlog");
	const auto sim = test::runEsif("simulate --config " + test::quoted(test::sourcePath("configs/sim/wrong_ids.ini")) +
								   " --out " + test::quoted(rawlog));
	ASSERT_EQ(sim.exit_code, 0) << sim.out;
	const auto truth = loadMeasurementTruth(groundTruthPrefixFor(rawlog), 3000);
	ASSERT_TRUE(truth);
	const Rawlog log = readRawlog(rawlog);
	std::set<MeasurementKey> misreads;
	for (std::size_t k = 0; k < log.true_ids.size(); ++k)
		for (std::size_t j = 0; j < log.true_ids[k].size(); ++j)
			if (log.true_ids[k][j] != (*truth)[k][j]) misreads.insert({k, j});
	ASSERT_GT(misreads.size(), 100u);  // 1% of about 14,000

	const Stats dropping = runAndReadStats("[esif]\nplugin = CeresFullSlam\n", rawlog, dir.file("drop"), dir);
	EXPECT_EQ(rejectedBy(dir.file("drop"), log.steps.size()), misreads);
	EXPECT_EQ(test::statNumber(dropping, "plugin_outliers_dropped"), static_cast<double>(misreads.size()));
	EXPECT_EQ(test::statNumber(dropping, "plugin_optimum_plausible"), 1);

	// The clean problem: the same log with the misreads rejected up front
	// (an associations.txt that keeps every other ID), solved plainly.
	std::vector<StepReport> reports(log.steps.size());
	for (std::size_t k = 0; k < log.steps.size(); ++k)
		for (std::size_t j = 0; j < log.true_ids[k].size(); ++j)
			reports[k].associations.push_back(
				misreads.count({k, j}) ? Association{Association::Kind::Rejected, -1}
									   : Association{Association::Kind::Matched, *log.true_ids[k][j]});
	std::filesystem::create_directory(dir.file("clean_ids"));
	writeAssociationFile(dir.file("clean_ids/associations.txt"), reports, "hand-made", rawlog);
	const Stats clean = runAndReadStats(
		"[esif]\nplugin = CeresFullSlam\nassociations_from = " + dir.file("clean_ids") + "\n[ceres_full]\noutliers = keep\n",
		rawlog, dir.file("clean"), dir);
	// The same problem solved to the same tolerance: the same cost, and the
	// landmarks within a millimetre (Ceres' stopping rule leaves converged
	// solutions up to ~1 mm apart along the map's rotation, see
	// test_CeresFullSimulated).
	EXPECT_NEAR(test::statNumber(dropping, "plugin_chi2"), test::statNumber(clean, "plugin_chi2"),
				1e-6 * test::statNumber(clean, "plugin_chi2"));
	EXPECT_EQ(test::statNumber(dropping, "plugin_chi2_dof"), test::statNumber(clean, "plugin_chi2_dof"));
	EXPECT_LT(largestLandmarkDifference(dir.file("clean"), dir.file("drop")), 1e-3);
}

TEST(CeresFullOutliers, ACleanLogKeepsEveryMeasurementAndThePlainOptimum)
{
	test::TempDir dir;
	const std::string rawlog = test::sourcePath("rawlogs/grid196.rawlog");
	const Stats dropping = runAndReadStats("[esif]\nplugin = CeresFullSlam\n", rawlog, dir.file("drop"), dir);
	const Stats keeping =
		runAndReadStats("[esif]\nplugin = CeresFullSlam\n[ceres_full]\noutliers = keep\n", rawlog, dir.file("keep"), dir);
	EXPECT_EQ(test::statNumber(dropping, "plugin_outliers_dropped"), 0);
	EXPECT_EQ(test::statNumber(dropping, "da_rejected"), 0);
	EXPECT_NEAR(test::statNumber(dropping, "plugin_chi2"), test::statNumber(keeping, "plugin_chi2"),
				1e-6 * test::statNumber(keeping, "plugin_chi2"));
	EXPECT_LT(largestLandmarkDifference(dir.file("keep"), dir.file("drop")), 1e-3);
}

}  // namespace
