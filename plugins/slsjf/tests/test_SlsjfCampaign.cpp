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
	test::expectInsideBands("SLSJF", slsjf);
	// Measured 5.1 cm against the optimum's 4.8 cm (1.07x): a third more is a regression.
	test::expectNearOptimum("SLSJF", slsjf, optimum);
}

}  // namespace
