// SLSJF (book Ch. 5) on local maps it did not build: the authors' own
// Victoria Park maps (../shared/data/localmaps/vicpark_200, third-party
// data, skipped when absent) against their Linear SLAM result and an
// independent implementation's figures (../shared/design/SLSJF.md §10), with
// and without the maps' feature IDs; and one-step local maps, whose
// relinearised joining is the full-SLAM optimum.

#include <EsifTestSupport.h>
#include <LocalMapTestSupport.h>

#include <esif/formats/RunOutputReader.h>
#include <esif/formats/StatsJson.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

namespace
{
using namespace esif;

const std::string kVicpark200 = test::sourcePath("../shared/data/localmaps/vicpark_200");

/// `esif run` of a committed local-map config on vicpark_200 against the
/// authors' Linear SLAM result; its stats.
Stats runOnVicpark200(const std::string& config, const test::TempDir& dir)
{
	const std::string out = dir.file(std::filesystem::path(config).stem().string());
	const auto r = test::runEsif(
		"run --quiet --config '" + test::sourcePath(config) + "' --local-maps '" + kVicpark200 +
		"' --reference-result '" + kVicpark200 + "/linear_slam_result' --out '" + out + "'");
	EXPECT_EQ(r.exit_code, 0) << r.out;
	return test::readStatsJson(out);
}

void print(const std::string& what, const Stats& s)
{
	const auto n = [&](const char* key) { return test::statNumber(s, key); };
	std::cout << what << ": " << n("landmarks") << " features, dimension " << n("state_dim") << ", non-zeros "
			  << n("info_nnz") << "; from Linear SLAM: features RMS " << n("refres_landmark_rms_m") << " m (max "
			  << n("refres_landmark_max_m") << "), end poses RMS " << n("refres_pose_rms_m") << " m, headings RMS "
			  << n("refres_heading_rms_deg") << " deg; wrong associations " << n("da_wrong") << ", features left out "
			  << n("da_rejected") << ", joined in " << n("wall_s") << " s\n";
}

TEST(SlsjfLocalMaps, VictoriaParkWithIdsMatchesTheIndependentImplementation)
{
	if (!std::filesystem::exists(kVicpark200)) GTEST_SKIP() << kVicpark200 << " not present";
	test::TempDir dir;
	const Stats plain = runOnVicpark200("configs/localmaps/slsjf.ini", dir);
	const Stats smoothed = runOnVicpark200("configs/localmaps/slsjf_smoothed.ini", dir);
	print("SLSJF", plain);
	print("SLSJF smoothed", smoothed);
	// Exact for this data and association (SLSJF.md §10): 200 poses of 3 and
	// 299 features of 2 scalars, and the numerical non-zeros of I, which do
	// not depend on the ordering or the linearisation.
	for (const Stats* s : {&plain, &smoothed})
	{
		EXPECT_EQ(test::statNumber(*s, "state_dim"), 1198);
		EXPECT_EQ(test::statNumber(*s, "poses_in_state"), 200);
		EXPECT_EQ(test::statNumber(*s, "landmarks"), 299);
		EXPECT_EQ(test::statNumber(*s, "info_nnz"), 134754);
		EXPECT_EQ(test::statNumber(*s, "da_wrong"), 0);
	}
	// The bounds from Linear SLAM's near-optimal features: the
	// independent implementation measured 0.420 m (plain) and 0.091 m
	// (relinearised).
	EXPECT_LT(test::statNumber(plain, "refres_landmark_rms_m"), 0.5);
	EXPECT_LT(test::statNumber(smoothed, "refres_landmark_rms_m"), 0.12);
	EXPECT_LT(test::statNumber(smoothed, "refres_pose_rms_m"), 0.1);
}

TEST(SlsjfLocalMaps, VictoriaParkWithoutIdsFindsEveryTree)
{
	if (!std::filesystem::exists(kVicpark200)) GTEST_SKIP() << kVicpark200 << " not present";
	test::TempDir dir;
	const Stats s = runOnVicpark200("configs/localmaps/slsjf_jcbb.ini", dir);
	print("SLSJF, JCBB on hidden IDs", s);
	// Every one of the 299 trees is mapped (each file ID is matched by a
	// global feature). Known limit, measured: 1 of 3,889 feature entries is
	// fused into a neighbouring tree, and 3 trees are mapped twice, where a
	// map's estimate of the tree lies 2.2-4.1 m (Mahalanobis d^2 19-27) from
	// the global one; gates wide enough to join those merge other trees
	// instead (4 to 20 wrong). da_wrong counts both kinds: 1 + 3.
	EXPECT_EQ(test::statNumber(s, "refres_landmarks_matched"), test::statNumber(s, "landmarks"));
	EXPECT_LE(test::statNumber(s, "da_wrong"), 4);
	EXPECT_LE(test::statNumber(s, "landmarks"), 302);
	EXPECT_LT(test::statNumber(s, "refres_landmark_rms_m"), 0.5);
}

TEST(SlsjfLocalMaps, OneStepMapsRelinearisedAreTheFullSlamOptimum)
{
	// With local maps of one step (odometry and one scan) and every map
	// relinearised at the end, SLSJF solves the full-SLAM problem of eq. 1.21
	// on the same measurements. The two optima still differ by each local
	// map's own linearisation (a new feature's Gaussian is fixed at its
	// range-bearing inverse, a second-order effect of about sigma_b^2 r =
	// 1.5 mm at 5 m): measured 3.8 mm RMS, 0.14 sigma at most. A quarter of
	// a sigma separates that from any modelling error.
	test::TempDir dir;
	ASSERT_EQ(test::simulateSmall(dir.file("small.rawlog")).exit_code, 0);
	std::ofstream(dir.file("slsjf.ini")) << "[esif]\nplugin = Slsjf\n[slsjf]\nassociation = known_ids\n"
											"local_map_steps = 1\nlocal_min_range_m = 0.3\nsmoothing = final\n"
											"smoothing_tolerance = 1e-10\nsmoothing_max_iterations = 30\n";
	// The baseline takes the measurements SLSJF used (the closest ones are left out).
	std::ofstream(dir.file("ceres.ini")) << "[esif]\nplugin = CeresFullSlam\nassociations_from = " << dir.file("slsjf")
										 << "\n";
	for (const char* name : {"slsjf", "ceres"})
	{
		const auto r = test::runEsif(
			"run --quiet --config '" + dir.file(std::string(name) + ".ini") + "' --rawlog '" +
			dir.file("small.rawlog") + "' --out '" + dir.file(name) + "'");
		ASSERT_EQ(r.exit_code, 0) << r.out;
	}
	const auto slsjf = readLandmarksTxt(dir.file("slsjf/landmarks.txt"));
	std::map<LandmarkId, LandmarkEstimate> optimum;
	for (const auto& lm : readLandmarksTxt(dir.file("ceres/landmarks.txt"))) optimum[lm.id] = lm;
	ASSERT_EQ(slsjf.size(), optimum.size());
	double largest_sigmas = 0;
	for (const auto& lm : slsjf)
	{
		const auto& o = optimum.at(lm.id);
		const double sigma = std::sqrt(o.cov.diagonal().maxCoeff());
		largest_sigmas = std::max(largest_sigmas, (lm.mean - o.mean).norm() / sigma);
	}
	std::cout << "one-step maps vs the full-SLAM optimum: largest landmark difference " << largest_sigmas
			  << " sigma\n";
	EXPECT_LT(largest_sigmas, 0.25);
}

}  // namespace
