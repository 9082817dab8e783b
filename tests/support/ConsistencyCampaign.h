#pragma once
/// \file ConsistencyCampaign.h
/// Small Monte Carlo campaigns for the plugin tests, and the two-sided
/// consistency bands they are held to. One run cannot decide consistency: a
/// run's landmark errors share the robot's error at their first sightings,
/// and its poses over steps share the drift, so a run's mean NEES is close
/// to a single chi-square draw. A few independent seeds of a small scenario
/// (configs/sim/small.ini: 200 steps, 16 features, under a second per run)
/// average that out.
///
/// The band: for d-dimensional errors, a run's mean NEES over its items has
/// mean d (consistent filter) and a variance between 2d / items
/// (independent items) and 2d (items fully correlated, one chi-square(d)
/// draw); the wider, fully correlated case is taken, so no correlation can
/// push a consistent filter out. The mean over R independent runs is then
/// chi-square(d R) / R, and the band is its two-sided (1 - alpha) interval.

#include <EsifTestSupport.h>

#include <esif/association/Chi2.h>
#include <esif/config/ConfigFile.h>
#include <esif/eval/Evaluator.h>
#include <esif/formats/GroundTruth.h>
#include <esif/sim/Simulator.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace esif::test
{
struct Band
{
	double lower = 0;
	double upper = 0;
	bool contains(double x) const { return x >= lower && x <= upper; }
};

/// The two-sided (1 - alpha) band of the mean over `runs` independent runs
/// of a per-run mean NEES of `dof`-dimensional errors, in the worst case of
/// fully correlated items (see above): chi2(dof runs) / runs quantiles.
inline Band meanNeesBand(int dof, int runs, double alpha = 0.01)
{
	return {chi2Quantile(alpha / 2, dof * runs) / runs, chi2Quantile(1 - alpha / 2, dof * runs) / runs};
}

/// One run of a campaign.
struct CampaignRun
{
	Accuracy accuracy;
	std::map<std::string, double> counters;
	std::size_t wrong_associations = 0;
};

/// Means over the runs of a campaign.
struct CampaignSummary
{
	std::vector<CampaignRun> runs;
	double landmark_nees = 0;  ///< mean over runs of the final landmarks' mean NEES (2 dof)
	double pose_nees = 0;  ///< mean over runs of the pose NEES averaged over steps (3 dof)
	double landmark_rmse_m = 0;	 ///< mean over runs of the landmark RMSE
	double ate_rmse_m = 0;	///< mean over runs of the trajectory RMSE
};

/// Seeds seed0 .. seed0 + runs - 1 of `scenario_ini` (a path below the
/// source tree), written once per test process into a shared folder.
inline std::string campaignRawlog(const std::string& scenario_ini, int seed)
{
	static TempDir dir;
	const std::string name = std::filesystem::path(scenario_ini).stem().string() + "_" + std::to_string(seed);
	const std::string path = dir.file(name + ".rawlog");
	if (!std::filesystem::exists(path))
	{
		Scenario s = Scenario::fromConfig(ConfigFile::load(sourcePath(scenario_ini)));
		s.seed = static_cast<decltype(s.seed)>(seed);
		Simulator(s).writeRawlog(path);
	}
	return path;
}

/// Runs plugin `plugin_class` configured by `section` on `runs` seeds of
/// `scenario_ini` and scores every run against its ground truth.
inline CampaignSummary runCampaign(
	const std::string& scenario_ini, int runs, const std::string& plugin_class, const std::string& section,
	bool hide_ids = false, int seed0 = 1)
{
	CampaignSummary c;
	for (int seed = seed0; seed < seed0 + runs; ++seed)
	{
		const std::string path = campaignRawlog(scenario_ini, seed);
		RawlogReadOptions options;
		options.hide_landmark_ids = hide_ids;
		const Rawlog log = readRawlog(path, options);
		auto plugin = makePlugin(plugin_class, section);
		const ReplayResult result = replay(*plugin, log, {0, false});
		CampaignRun r;
		r.accuracy = scoreAgainstTruth(result, groundTruthPrefixFor(path));
		r.counters = countersOf(*plugin);
		r.wrong_associations = result.audit.wrongCount();
		EXPECT_TRUE(r.accuracy.landmark_nees_mean && r.accuracy.pose_nees_mean && r.accuracy.landmark_rmse_m &&
					r.accuracy.ate_rmse_m)
			<< plugin_class << " seed " << seed << ": no NEES or RMSE";
		c.landmark_nees += r.accuracy.landmark_nees_mean.value_or(NAN) / runs;
		c.pose_nees += r.accuracy.pose_nees_mean.value_or(NAN) / runs;
		c.landmark_rmse_m += r.accuracy.landmark_rmse_m.value_or(NAN) / runs;
		c.ate_rmse_m += r.accuracy.ate_rmse_m.value_or(NAN) / runs;
		c.runs.push_back(r);
	}
	return c;
}

/// One line for the test log: the campaign's means and bands.
inline void printCampaign(const std::string& what, const CampaignSummary& c, const Band& landmark, const Band& pose)
{
	std::cout << what << " over " << c.runs.size() << " runs: landmark NEES " << c.landmark_nees << " (band ["
			  << landmark.lower << ", " << landmark.upper << "]), pose NEES " << c.pose_nees << " (band ["
			  << pose.lower << ", " << pose.upper << "]), landmark RMSE " << c.landmark_rmse_m << " m, ATE "
			  << c.ate_rmse_m << " m\n";
}

/// Prints the campaign and expects its mean landmark and pose NEES inside
/// their two-sided bands for its number of runs (meanNeesBand).
inline void expectInsideBands(const std::string& what, const CampaignSummary& c)
{
	const int runs = static_cast<int>(c.runs.size());
	const Band landmark = meanNeesBand(2, runs), pose = meanNeesBand(3, runs);
	printCampaign(what, c, landmark, pose);
	EXPECT_TRUE(landmark.contains(c.landmark_nees)) << what << ": " << c.landmark_nees;
	EXPECT_TRUE(pose.contains(c.pose_nees)) << what << ": " << c.pose_nees;
}

/// Expects the campaign's landmark RMSE within [0.9, `above`] times the
/// optimum's on the same seeds: the optimum is the optimum (0.9 leaves room
/// for ten draws), and the tests' comments say where each `above` comes from.
inline void expectNearOptimum(const std::string& what, const CampaignSummary& c, const CampaignSummary& optimum,
							  double above = 1.3)
{
	std::cout << "landmark RMSE: " << what << " " << c.landmark_rmse_m << " m, optimum " << optimum.landmark_rmse_m
			  << " m\n";
	EXPECT_LT(c.landmark_rmse_m, above * optimum.landmark_rmse_m) << what;
	EXPECT_GT(c.landmark_rmse_m, 0.9 * optimum.landmark_rmse_m) << what;
}

}  // namespace esif::test
