// The filters of configs/vicpark/ on Victoria Park, held against
// the full-SLAM optimum of the same rawlog under the same calibrated noise
// (there is no ground truth): each map near the optimum's, with at least 95%
// of the optimum's trees inside the filter's own 95% ellipses (a consistent
// filter puts 95% there, and the optimum's own error is shared, so fewer is
// over-confidence). The filters' 0.9999 gates and the optimum's 5-sigma
// rule both leave out the dataset's wrong tree IDs, but not the same
// handful of the conflicting measurements around them (the gates decide at
// fusion time, the optimum on the whole log): 17 against 11, measured 1.3
// to 1.8 m RMS apart, inside the trees' own uncertainty (99% inside). Each
// filter keeps at least 148 of the 151 trees: a tree whose first sighting
// fails its gate later is left out with it. Each filter's twin with the
// tree IDs hidden is held to issue 40's targets against them.
// Skipped without the dataset (third-party, never committed).

#include <EsifTestSupport.h>

#include <esif/eval/RunDifference.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/formats/StatsJson.h>

#include <gtest/gtest.h>

namespace
{
using namespace esif;

class VicparkFilters : public ::testing::Test
{
   protected:
	static void SetUpTestSuite()
	{
		dir_ = std::make_unique<test::TempDir>();
		rawlog_ = test::importVictoriaPark(*dir_);
		if (rawlog_) run("ceres_full");
	}
	static void TearDownTestSuite() { dir_.reset(); }
	void SetUp() override
	{
		if (!rawlog_) GTEST_SKIP() << test::victoriaParkDataset() << " not present";
	}

	static std::string run(const std::string& config)
	{
		const std::string out = dir_->file(config);
		const auto r = test::runEsif("run -q --config " + test::quoted(test::sourcePath("configs/vicpark/" + config + ".ini")) +
									 " --rawlog " + test::quoted(*rawlog_) + " --out " + test::quoted(out));
		EXPECT_EQ(r.exit_code, 0) << r.out;
		return out;
	}

	/// The run of `config` against the optimum.
	static RunDifference fromOptimum(const std::string& config)
	{
		// Both runs have the tree IDs: paired through them, no cut-off needed.
		const RunDifference d =
			runDifference(readRunOutputs(run(config)), readRunOutputs(dir_->file("ceres_full")), std::nullopt);
		EXPECT_EQ(d.pairing, LandmarkPairing::TrueLandmark);
		std::cout << config << ": " << *d.landmark_rms_m << " m RMS from the optimum, rotation "
				  << *d.best_fit_rotation_deg << " deg, " << 100 * *d.landmarks_inside_own95_fraction
				  << "% inside their own 95% ellipse\n";
		return d;
	}

	/// Near the optimum and consistent: at least 148 trees, RMS below
	/// `max_rms_m`, 95% inside their own 95% ellipse.
	static void expectNearAndConsistent(const std::string& config, double max_rms_m)
	{
		const RunDifference d = fromOptimum(config);
		EXPECT_GE(d.landmarks_matched, 148u);
		EXPECT_LT(*d.landmark_rms_m, max_rms_m);
		EXPECT_GE(*d.landmarks_inside_own95_fraction, 0.95);
	}

	/// The targets for a filter run with the tree IDs hidden, scored
	/// against them, beside its twin with IDs: recall (loosened by one
	/// point, 95%: 94%, so that one wrong loop closure shows), precision,
	/// 151 +- 8 landmarks, at most 1.5 times the twin's distance from the
	/// optimum.
	static void expectNoIdTargets(const std::string& config, const std::string& twin)
	{
		const std::string out = run(config);
		const Stats stats = Stats::load(out + "/stats.json");
		EXPECT_GE(*stats.number("da_recall"), 0.94);
		EXPECT_GE(*stats.number("da_precision"), 0.95);
		EXPECT_NEAR(*stats.number("landmarks"), 151, 8);
		const RunDifference d =
			runDifference(readRunOutputs(out), readRunOutputs(dir_->file("ceres_full")), std::nullopt);
		EXPECT_EQ(d.pairing, LandmarkPairing::TrueLandmark);
		const RunDifference with_ids = fromOptimum(twin);
		std::cout << config << ": recall " << *stats.number("da_recall") << ", " << *d.landmark_rms_m
				  << " m RMS from the optimum\n";
		EXPECT_LT(*d.landmark_rms_m, 1.5 * *with_ids.landmark_rms_m);
	}

	static std::unique_ptr<test::TempDir> dir_;
	static std::optional<std::string> rawlog_;
};
std::unique_ptr<test::TempDir> VicparkFilters::dir_;
std::optional<std::string> VicparkFilters::rawlog_;

TEST_F(VicparkFilters, SlsjfIsWithinThreeMetresOfTheOptimumAndConsistent)
{
	expectNearAndConsistent("slsjf", 2.5);
}

TEST_F(VicparkFilters, MapJoiningIsWithinThreeMetresOfTheOptimumAndConsistent)
{
	expectNearAndConsistent("dslam_lmj", 2.5);
}

TEST_F(VicparkFilters, SmoothedSlsjfIsNearerTheOptimumThanThePlainFilter)
{
	// Relinearised, the map keeps only the differences in the measurements
	// left out (above): 1.3 m against the plain SLSJF's 1.56 m.
	expectNearAndConsistent("slsjf_smoothed", 1.5);
}

TEST_F(VicparkFilters, OnlineSlsjfWithShortMapsIsAsNearAsTheSmoothedOne)
{
	expectNearAndConsistent("slsjf_online", 1.5);
}

TEST_F(VicparkFilters, MapJoiningWithoutIdsFindsTheTreesNearTheOptimum)
{
	// dslam_lmj_jcbb.ini: start-pose frame, 50-step maps, new features
	// judged given the accepted pairs. Measured: recall 96.1%, precision
	// 96.7%, 155 landmarks (146 trees, 9 duplicated), 2.29 m from the
	// optimum where the twin with IDs is 1.83 m; the failing runs of
	// docs/results/no_ids.md are below 86%.
	expectNoIdTargets("dslam_lmj_jcbb", "dslam_lmj");
}

TEST_F(VicparkFilters, DslamIsWithinTwoAndAHalfMetresOfTheOptimumAndConsistent)
{
	// Measured: 1.67 m, every tree inside its own 95% ellipse (the book's
	// local SLAM, dropping a tree the first scan that misses it: 1.86 m).
	expectNearAndConsistent("dslam", 2.5);
}

TEST_F(VicparkFilters, DslamWithoutIdsFindsTheTreesNearTheOptimum)
{
	// dslam_jcbb.ini: trees held out of view for 1000 steps anchor the
	// relative tests of lone sightings. Measured: recall 95.9%, precision
	// 96.8%, 151 landmarks (144 trees, 7 duplicated), 2.36 m from the
	// optimum where the twin with IDs is 1.67 m; the sweep's failing runs
	// (docs/results/no_ids.md) are below 85%, its good ones 95.8-96.3%.
	expectNoIdTargets("dslam_jcbb", "dslam");
}

TEST_F(VicparkFilters, TheEkfAndSlsjfWithoutIdsMeetTheTargets)
{
	// Measured (docs/results/no_ids.md): recall 95.1-96.5%, precision
	// 96.7-96.9%, 153-156 landmarks, 0.97-1.44 times the twin's distance
	// from the optimum (SLSJF's 1.44 is the closest to its bound).
	for (const std::string twin : {"ekf", "slsjf", "slsjf_online", "slsjf_smoothed"})
	{
		SCOPED_TRACE(twin + "_jcbb");
		expectNoIdTargets(twin + "_jcbb", twin);
	}
}

}  // namespace
