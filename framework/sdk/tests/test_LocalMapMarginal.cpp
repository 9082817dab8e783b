// marginaliseFeatures: the kept part of a local map must carry exactly the
// map's marginal over it, in both of the map's forms.
#include <LocalMapTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/localmap/LocalMapMarginal.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>

using namespace esif;

namespace
{
/// Rows of the end pose and of the features flagged in `keep`.
std::vector<Eigen::Index> keptRows(const std::vector<bool>& keep)
{
	std::vector<Eigen::Index> rows = {0, 1, 2};
	for (std::size_t i = 0; i < keep.size(); ++i)
		if (keep[i]) rows.push_back(static_cast<Eigen::Index>(3 + 2 * i)), rows.push_back(static_cast<Eigen::Index>(4 + 2 * i));
	return rows;
}
}  // namespace

TEST(LocalMapMarginal, KeepsTheMarginalOfTheKeptFeatures)
{
	// A random map's information is dense, so every dropped feature is
	// correlated with every kept one: the Schur complement must remove
	// exactly their shared information. Its inverse is the kept block of the
	// covariance, to the precision of two 13 x 13 Cholesky solves.
	const LocalMap map = test::randomLocalMap(3, 5, 11);
	const std::vector<bool> keep = {true, false, true, false, true};
	const LocalMap kept = marginaliseFeatures(map, keep);

	ASSERT_EQ(kept.features.size(), 3u);
	EXPECT_EQ(kept.features[1].id, map.features[2].id);
	EXPECT_EQ(kept.state()(5), map.features[2].position.x());
	EXPECT_EQ(kept.end_pose, map.end_pose);
	const Eigen::MatrixXd P = map.information.inverse();
	const Eigen::MatrixXd expected = P(keptRows(keep), keptRows(keep));
	EXPECT_LT((kept.information.inverse() - expected).norm(), 1e-10 * expected.norm());
	EXPECT_EQ(kept.information, kept.information.transpose());
	EXPECT_FALSE(kept.covariance.has_value());	// a map read from files has none
	EXPECT_NO_THROW(kept.validate("test"));
}

TEST(LocalMapMarginal, KeepsTheCovarianceBlockOfAMapBuiltHere)
{
	LocalMap map = test::randomLocalMap(2, 4, 5);
	map.covariance = map.information.inverse();
	const std::vector<bool> keep = {false, true, true, false};
	const LocalMap kept = marginaliseFeatures(map, keep);
	ASSERT_TRUE(kept.covariance.has_value());
	EXPECT_EQ(*kept.covariance, Eigen::MatrixXd((*map.covariance)(keptRows(keep), keptRows(keep))));
	EXPECT_LT((kept.information * *kept.covariance - Eigen::MatrixXd::Identity(7, 7)).norm(), 1e-9);
}

TEST(LocalMapMarginal, KeepingEverythingChangesNothing)
{
	const LocalMap map = test::randomLocalMap(1, 3, 2);
	const LocalMap kept = marginaliseFeatures(map, {true, true, true});
	EXPECT_EQ(kept.information, map.information);
	EXPECT_EQ(kept.features.size(), 3u);
}

TEST(LocalMapMarginal, RejectsWrongSizesAndANonPositiveDroppedBlock)
{
	LocalMap map = test::randomLocalMap(4, 2, 3);
	EXPECT_THROW(marginaliseFeatures(map, {true}), std::invalid_argument);
	LocalMap truncated = map;
	truncated.information = map.information.topLeftCorner(5, 5);
	EXPECT_THROW(marginaliseFeatures(truncated, {true, false}), std::invalid_argument);
	map.information.block<2, 2>(5, 5).setZero();	// feature 2's own information gone
	try
	{
		marginaliseFeatures(map, {true, false});
		FAIL() << "a dropped block without information was eliminated";
	}
	catch (const NumericalError& e)
	{
		EXPECT_NE(std::string(e.what()).find("local map 4"), std::string::npos) << e.what();
	}
}
