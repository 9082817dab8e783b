#include <esif/association/Chi2.h>
#include <esif/eval/AssociationAudit.h>
#include <esif/compare/ComparisonTable.h>
#include <esif/eval/Evaluator.h>
#include <esif/formats/StatsJson.h>

#include <gtest/gtest.h>

namespace
{
using namespace esif;

TEST(Chi2, MatchesTabulatedQuantiles)
{
	// Standard table values (Abramowitz & Stegun 26.4).
	EXPECT_NEAR(chi2Quantile(0.95, 2), 5.991, 5e-4);
	EXPECT_NEAR(chi2Quantile(0.95, 3), 7.815, 5e-4);
	EXPECT_NEAR(chi2Quantile(0.99, 2), 9.210, 5e-4);
	EXPECT_NEAR(chi2Quantile(0.95, 1), 3.841, 5e-4);
	EXPECT_NEAR(chi2Quantile(0.95, 10), 18.307, 5e-4);
	EXPECT_NEAR(chi2Cdf(chi2Quantile(0.3, 7), 7), 0.3, 1e-9);
}

TEST(Evaluator, RmseAteAndNeesOnAHandMadeCase)
{
	GroundTruth truth;
	truth.landmarks = {{1, {0, 0}}, {2, {10, 0}}};
	truth.path = {Pose2(0, 0, 0), Pose2(1, 0, 0)};
	Estimate est;
	// Errors 0.3 m and 0.4 m with variance 0.01 m^2 per axis: NEES 9 and 16.
	est.landmarks = {{1, {0.3, 0}, 0.01 * Eigen::Matrix2d::Identity()},
					 {2, {10, 0.4}, 0.01 * Eigen::Matrix2d::Identity()}};
	std::vector<TrajectoryPoint> traj = {{0, 0, {{0, 0, 0}, Eigen::Matrix3d::Zero()}},
										 {1, 1, {{1, 0.1, 0}, 0.01 * Eigen::Matrix3d::Identity()}}};
	const auto acc = evaluate(truth, traj, est, {{1, 1}, {2, 2}});
	EXPECT_NEAR(*acc.landmark_rmse_m, std::sqrt((0.09 + 0.16) / 2), 1e-12);
	EXPECT_NEAR(*acc.landmark_nees_mean, 12.5, 1e-9);
	EXPECT_EQ(*acc.landmark_consistent_fraction, 0.0);
	EXPECT_NEAR(*acc.ate_rmse_m, std::sqrt(0.01 / 2), 1e-12);
	EXPECT_NEAR(*acc.pose_nees_mean, 1.0, 1e-9);  // the exact initial pose is not scored
}

TEST(AssociationAudit, CountsWrongAndSplitAssociations)
{
	AssociationAudit audit;
	using K = Association::Kind;
	audit.record({{{K::New, 100}, {K::New, 101}}}, {LandmarkId(1), LandmarkId(2)});
	audit.record({{{K::Matched, 100}, {K::Matched, 100}, {K::Rejected, -1}}}, {LandmarkId(1), LandmarkId(2), LandmarkId(2)});
	audit.record({{{K::New, 102}}}, {LandmarkId(1)});  // true landmark 1 split over two
	EXPECT_EQ(audit.newCount(), 3u);
	EXPECT_EQ(audit.matchedCount(), 2u);
	EXPECT_EQ(audit.rejectedCount(), 1u);
	EXPECT_EQ(audit.wrongCount(), 2u);	// one measurement of 2 put on 100, one duplicate of 1
	EXPECT_EQ(audit.filterToTrue().at(100), 1);
}

TEST(Stats, JsonRoundTripAndCsv)
{
	Stats s;
	s.set("plugin", StatValue(std::string("EkfSlam")));
	s.set("steps", StatValue(3000LL));
	s.set("wall_s", StatValue(0.25));
	s.set("info_nnz", StatValue(nullptr));
	s.set("label", StatValue(std::string("a,\"b\"")));
	const auto back = Stats::fromJson(s.toJson(), "t");
	EXPECT_EQ(*back.number("steps"), 3000);
	EXPECT_EQ(*back.number("wall_s"), 0.25);
	EXPECT_FALSE(back.number("info_nnz"));
	const auto csv = comparisonCsv({s, back});
	EXPECT_NE(csv.find("plugin,steps,wall_s,info_nnz,label\n"), std::string::npos) << csv;
	EXPECT_NE(csv.find("EkfSlam,3000,0.25,,\"a,\"\"b\"\"\""), std::string::npos) << csv;
}

}  // namespace
