// The map-joining filters of configs/vicpark/ on Victoria Park, held against
// the full-SLAM optimum of the same rawlog (there is no ground truth): each
// map within 3 m RMS of the optimum's with at least 80% of the optimum's
// trees inside the filter's own 95% ellipses (a consistent filter puts 95%
// there, and the optimum's own error is shared, so fewer is over-confidence).
// Skipped without the dataset (third-party, never committed).

#include <EsifTestSupport.h>

#include <esif/eval/RunDifference.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/formats/StatsJson.h>

#include <gtest/gtest.h>

namespace
{
using namespace esif;

class VicparkMapJoining : public ::testing::Test
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

	static std::unique_ptr<test::TempDir> dir_;
	static std::optional<std::string> rawlog_;
};
std::unique_ptr<test::TempDir> VicparkMapJoining::dir_;
std::optional<std::string> VicparkMapJoining::rawlog_;

TEST_F(VicparkMapJoining, SlsjfIsWithinThreeMetresOfTheOptimumAndConsistent)
{
	const RunDifference d = fromOptimum("slsjf");
	EXPECT_EQ(d.landmarks_matched, 151u);
	EXPECT_LT(*d.landmark_rms_m, 3.0);
	EXPECT_GE(*d.landmarks_inside_own95_fraction, 0.80);
}

TEST_F(VicparkMapJoining, MapJoiningIsWithinThreeMetresOfTheOptimumAndConsistent)
{
	const RunDifference d = fromOptimum("dslam_lmj");
	EXPECT_EQ(d.landmarks_matched, 151u);
	EXPECT_LT(*d.landmark_rms_m, 3.0);
	EXPECT_GE(*d.landmarks_inside_own95_fraction, 0.80);
}

TEST_F(VicparkMapJoining, SmoothedSlsjfReachesTheOptimumWithinTheTreesUncertainty)
{
	const RunDifference d = fromOptimum("slsjf_smoothed");
	// Well inside the trees' own uncertainty (larger axis: median 1.45 m, 5% below 0.28 m).
	EXPECT_LT(*d.landmark_rms_m, 0.5);
	EXPECT_GE(*d.landmarks_inside_own95_fraction, 0.95);
}

TEST_F(VicparkMapJoining, OnlineSlsjfWithShortMapsIsWithinFifteenCentimetresOfTheOptimum)
{
	const RunDifference d = fromOptimum("slsjf_online");
	// The target of configs/vicpark/slsjf_online.ini: 0.15 m RMS, a tenth of
	// the trees' median uncertainty, and a consistent filter's 95% inside.
	EXPECT_EQ(d.landmarks_matched, 151u);
	EXPECT_LT(*d.landmark_rms_m, 0.15);
	EXPECT_GE(*d.landmarks_inside_own95_fraction, 0.95);
}

}  // namespace
