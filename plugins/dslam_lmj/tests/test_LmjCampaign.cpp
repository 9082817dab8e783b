// D-SLAM local map joining's consistency held from both sides over a small
// campaign (ConsistencyCampaign.h: 10 seeds of configs/sim/small.ini), and
// its accuracy against the full-SLAM optimum on the same seeds.

#include <ConsistencyCampaign.h>

#include <gtest/gtest.h>

namespace
{
using namespace esif;

constexpr int kRuns = 10;
const std::string kScenario = "configs/sim/small.ini";

TEST(LmjCampaign, ConsistentFromBothSidesAndNearTheOptimum)
{
	const auto lmj = test::runCampaign(kScenario, kRuns, "DslamLocalMapJoining", "");
	const auto optimum = test::runCampaign(kScenario, kRuns, "CeresFullSlam", "");
	// Bands for 10 runs at alpha = 0.01: landmarks [0.74, 4.00], poses
	// [1.38, 5.37]. Measured 3.10 and 3.63 (book Ch. 4: local map joining
	// with small local maps is close to consistent).
	test::expectInsideBands("D-SLAM local map joining", lmj);
	// Measured 5.1 cm against the optimum's 4.8 cm (1.07x); the trajectory,
	// fused only when a local map closes, 6.5 cm against 3.7 cm.
	test::expectNearOptimum("LMJ", lmj, optimum);
	EXPECT_LT(lmj.ate_rmse_m, 2.5 * optimum.ate_rmse_m);
}

}  // namespace
