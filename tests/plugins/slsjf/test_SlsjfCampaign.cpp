// SLSJF's consistency held from both sides over a small campaign
// (ConsistencyCampaign.h: 10 seeds of configs/sim/small.ini), and its
// accuracy against the full-SLAM optimum on the same seeds.

#include <ConsistencyCampaign.h>

#include <gtest/gtest.h>

namespace
{
using namespace esif;

constexpr int kRuns = 10;
const std::string kScenario = "configs/sim/small.ini";

TEST(SlsjfCampaign, ConsistentFromBothSidesAndNearTheOptimum)
{
	const auto slsjf = test::runCampaign(kScenario, kRuns, "Slsjf", "");
	const auto optimum = test::runCampaign(kScenario, kRuns, "CeresFullSlam", "");
	// Bands for 10 runs at alpha = 0.01: landmarks [0.74, 4.00], poses
	// [1.38, 5.37]. Measured 3.07 and 3.48: SLSJF with small local maps is
	// consistent (book Sec. 5.4), a little above the optimum's 2.6 through
	// each local map's EKF linearisation.
	const auto landmark_band = test::meanNeesBand(2, kRuns), pose_band = test::meanNeesBand(3, kRuns);
	test::printCampaign("SLSJF", slsjf, landmark_band, pose_band);
	EXPECT_TRUE(landmark_band.contains(slsjf.landmark_nees)) << slsjf.landmark_nees;
	EXPECT_TRUE(pose_band.contains(slsjf.pose_nees)) << slsjf.pose_nees;
	// Measured 5.1 cm against the optimum's 4.8 cm (1.07x): a third more is a regression.
	std::cout << "landmark RMSE: SLSJF " << slsjf.landmark_rmse_m << " m, optimum " << optimum.landmark_rmse_m
			  << " m\n";
	EXPECT_LT(slsjf.landmark_rmse_m, 1.3 * optimum.landmark_rmse_m);
	EXPECT_GT(slsjf.landmark_rmse_m, 0.9 * optimum.landmark_rmse_m);
}

}  // namespace
