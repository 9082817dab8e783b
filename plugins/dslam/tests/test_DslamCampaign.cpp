// The D-SLAM plugin's consistency held from both sides over a small
// campaign (ConsistencyCampaign.h: 10 seeds of configs/sim/small.ini), its
// accuracy against the full-SLAM optimum on the same seeds, and the options
// no other end-to-end test selects: `fusion = joint` and the `pcg` and
// `fresh_cholesky` recoveries.

#include <ConsistencyCampaign.h>

#include <gtest/gtest.h>

namespace
{
using namespace esif;

constexpr int kRuns = 10;
const std::string kScenario = "configs/sim/small.ini";

const test::CampaignSummary& defaultDslam()
{
	static const auto c = test::runCampaign(kScenario, kRuns, "Dslam", "association = known_ids\n");
	return c;
}

TEST(DslamCampaign, ConsistentFromBothSidesAndNearTheOptimum)
{
	// Bands for 10 runs at alpha = 0.01: landmarks [0.74, 4.00], poses
	// [1.38, 5.37]; measured 2.73 and 2.92. D-SLAM is built to be
	// conservative (CI in the localisation, Sec. 3.4), so the side that
	// matters is the lower one: its covariance would have to be ~3.7x too
	// large to fall under it; the band's lower edge, 0.37 of the dof, is
	// above the 0.2 x dof a conservative filter may reach at worst.
	const auto& dslam = defaultDslam();
	test::expectInsideBands("D-SLAM", dslam);
	// Accuracy on the same seeds as the optimum (measured 4.77 cm vs the
	// optimum's 4.76 cm: on this small map D-SLAM loses almost nothing).
	// The book's D-SLAM drops the robot-map information of z_rob, so it may
	// be worse; by a third would be a regression.
	const auto optimum = test::runCampaign(kScenario, kRuns, "CeresFullSlam", "");
	test::expectNearOptimum("D-SLAM", dslam, optimum);
}

TEST(DslamCampaign, JointFusionConsistentFromBothSides)
{
	// `fusion = joint`: the CI fusion over robot and map (Sec. 3.4.2)
	// instead of the robot alone. The map is the same (measured landmark
	// NEES 2.74, RMSE 4.78 cm); the localisation follows the map's
	// estimate more closely, so its pose NEES (4.38) and ATE (6.2 cm vs
	// 4.5 cm) are higher, still inside the band.
	const auto joint = test::runCampaign(kScenario, kRuns, "Dslam", "association = known_ids\nfusion = joint\n");
	test::expectInsideBands("D-SLAM joint fusion", joint);
	EXPECT_LT(joint.landmark_rmse_m, 1.1 * defaultDslam().landmark_rmse_m);
	EXPECT_LT(joint.ate_rmse_m, 2.0 * defaultDslam().ate_rmse_m);
}

TEST(DslamCampaign, PcgAndFreshCholeskyRecoveriesGiveTheSameEstimates)
{
	// The three recoveries solve the same linear systems (Sec. 3.3.2); PCG
	// stops at a relative residual of 1e-10 by default, far below what
	// moves a mean NEES in its fourth digit (measured equal to all digits
	// printed).
	for (const std::string recovery : {"pcg", "fresh_cholesky"})
	{
		const auto c =
			test::runCampaign(kScenario, kRuns, "Dslam", "association = known_ids\nrecovery = " + recovery + "\n");
		test::expectInsideBands("D-SLAM recovery = " + recovery, c);
		EXPECT_NEAR(c.landmark_nees, defaultDslam().landmark_nees, 1e-4 * defaultDslam().landmark_nees) << recovery;
		EXPECT_NEAR(c.pose_nees, defaultDslam().pose_nees, 1e-4 * defaultDslam().pose_nees) << recovery;
		EXPECT_NEAR(c.landmark_rmse_m, defaultDslam().landmark_rmse_m, 1e-6) << recovery;
		// ... and each did recover that way: PCG solves, or a fresh
		// factorisation at every change (no partial refactorisation).
		const auto& counters = c.runs.front().counters;
		if (recovery == "pcg")
		{
			EXPECT_GT(counters.at("sparse_pcg_solves"), 0);
		}
		if (recovery == "fresh_cholesky")
		{
			EXPECT_EQ(counters.at("sparse_partial_refactorisations"), 0);
			EXPECT_EQ(counters.at("sparse_pcg_solves"), 0);
		}
	}
	EXPECT_EQ(defaultDslam().runs.front().counters.at("sparse_pcg_solves"), 0);
}

}  // namespace
