// Merging two landmarks of the EKF into one (EkfSlamCore::mergeLandmarks,
// CoincidentLandmarks): the merged state against the Gaussian conditioned on
// the two being one point, derived another way (by substitution in the
// information form), and the bookkeeping that picks and records merges.

#include "EkfCoreFixture.h"
#include "TwoUnresolvedPoints.h"

#include <esif/ekf/CoincidentLandmarks.h>
#include <esif/ekf/EkfSlamCore.h>
#include <esif/ekf/LandmarkEkf.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

namespace
{
using namespace esif;

/// Three landmarks; 0 and 2 are sightings of points about 0.2 m apart, 1 is
/// 2 m from them.
EkfSlamCore threeLandmarks() { return test::coreWithThreeLandmarks({2.6, 0.2}); }

TEST(LandmarkMerge, MergedStateIsTheGaussianConditionedOnOnePoint)
{
	EkfSlamCore core = threeLandmarks();
	const Eigen::VectorXd x = core.state();
	const Eigen::MatrixXd P = core.covariance();

	// Independently: restrict the Gaussian to the subspace x_l2 = x_l0. With
	// T mapping [robot; l0; l1] to [robot; l0; l1; l0], the posterior's
	// information is T^T Y T and its information vector T^T Y x (Y = P^-1):
	// a dense 9x9 inverse, fine for a test.
	Eigen::MatrixXd T = Eigen::MatrixXd::Zero(9, 7);
	T.topLeftCorner(7, 7).setIdentity();
	T.block<2, 2>(7, 3).setIdentity();
	const Eigen::MatrixXd Y = P.inverse();
	const Eigen::MatrixXd Y_merged = T.transpose() * Y * T;
	const Eigen::VectorXd x_merged = Y_merged.ldlt().solve(T.transpose() * Y * x);
	const Eigen::MatrixXd P_merged = Y_merged.inverse();

	ASSERT_TRUE(core.mergeLandmarks(0, 2));
	ASSERT_EQ(core.landmarkCount(), 2u);
	// Both routes are exact algebra on the same Gaussian; the tolerance is a
	// few hundred ulps of the entries (variances ~1e-2, means ~1).
	EXPECT_LT((core.state() - x_merged).lpNorm<Eigen::Infinity>(), 1e-10);
	EXPECT_LT((core.covariance() - P_merged).lpNorm<Eigen::Infinity>(), 1e-12);
	EXPECT_EQ(core.covariance(), core.covariance().transpose());
	EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(core.covariance()).info(), Eigen::Success);
}

TEST(LandmarkMerge, CoincidenceDistanceIsTheMahalanobisNormOfTheDifference)
{
	const EkfSlamCore core = threeLandmarks();
	const Eigen::MatrixXd P = core.covariance();
	Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2, 9);
	A.block<2, 2>(0, 3).setIdentity();
	A.block<2, 2>(0, 7) = -Eigen::Matrix2d::Identity();
	const Eigen::Vector2d d = A * core.state();
	const double expected = d.dot((A * P * A.transpose()).ldlt().solve(d));
	EXPECT_NEAR(core.coincidenceDistance2(0, 2), expected, 1e-9 * expected);
	EXPECT_NEAR(core.coincidenceDistance2(2, 0), expected, 1e-9 * expected);
}

TEST(LandmarkMerge, APairWhoseDifferenceIsCertainIsNotMerged)
{
	// Landmark 1 an exact copy of landmark 0, correlations included: their
	// difference has zero covariance, and a merge would divide by it.
	const EkfSlamCore base = threeLandmarks();
	Eigen::VectorXd x = base.state().head(7);
	Eigen::MatrixXd P = base.covariance().topLeftCorner(7, 7);
	x.segment<2>(5) = x.segment<2>(3);
	P.middleRows<2>(5) = P.middleRows<2>(3);
	P.middleCols<2>(5) = P.middleCols<2>(3);
	EkfSlamCore core;
	core.setState(x, P);
	EXPECT_FALSE(core.mergeLandmarks(0, 1));
	EXPECT_EQ(core.landmarkCount(), 2u);
	EXPECT_EQ(core.state(), x);
}

TEST(LandmarkMerge, OnlyLandmarksMatchedOftenEnoughAreMergedAndTheClosestPairFirst)
{
	const EkfSlamCore core = threeLandmarks();
	const std::vector<LandmarkId> ids = {10, 11, 12};
	const double d02 = core.coincidenceDistance2(0, 2);
	ASSERT_LT(d02, std::min(core.coincidenceDistance2(0, 1), core.coincidenceDistance2(1, 2)));
	// A gate just above the pair (0, 2) (exp(-d2/2) is the chi-square(2) tail).
	CoincidentLandmarks merging(2, 1 - std::exp(-0.5 * (d02 + 1)));
	for (const LandmarkId id : ids) merging.countMatch(id);
	EXPECT_FALSE(merging.nextPair(core, ids)) << "each matched once, two needed";
	merging.countMatch(10);
	merging.countMatch(11);
	EXPECT_FALSE(merging.nextPair(core, ids)) << "landmark 12 still matched once";
	merging.countMatch(12);
	EXPECT_EQ(merging.nextPair(core, ids), std::make_pair(std::size_t{0}, std::size_t{2}));
	EXPECT_FALSE(CoincidentLandmarks(0).nextPair(core, ids)) << "0 = off";
}

TEST(LandmarkMerge, APairBeyondTheGateIsKeptApart)
{
	const EkfSlamCore core = threeLandmarks();
	const std::vector<LandmarkId> ids = {10, 11, 12};
	const double d2 = core.coincidenceDistance2(0, 2);
	ASSERT_GT(d2, 0.1);  // a gate quantile just below it stays in (0, 1)
	// exp(-d2/2) is the chi-square(2) tail: a quantile just below d2 must keep them apart.
	CoincidentLandmarks merging(1, 1 - std::exp(-0.5 * d2) - 1e-9);
	for (const LandmarkId id : ids) merging.countMatch(id);
	const auto pair = merging.nextPair(core, ids);
	EXPECT_TRUE(!pair || *pair != std::make_pair(std::size_t{0}, std::size_t{2}));
}

TEST(LandmarkMerge, MergesAreRecordedSoEarlierReportsCanNameTheLandmarkTheyBecame)
{
	CoincidentLandmarks merging(1);
	merging.recordMerge(3, 7);
	merging.recordMerge(1, 3);
	EXPECT_EQ(merging.finalId(7), 1);
	EXPECT_EQ(merging.finalId(3), 1);
	EXPECT_EQ(merging.finalId(1), 1);
	EXPECT_EQ(merging.finalId(5), 5);
	EXPECT_EQ(merging.standsFor(1), 3);
	EXPECT_EQ(merging.standsFor(5), 1);
	EXPECT_EQ(merging.merges(), 2u);
}

using test::standingBesideTwoUnresolvedPoints;

EkfAssociationParams jcbbMergingAfter(int matches)
{
	EkfAssociationParams p;
	p.association = EkfAssociation::Jcbb;
	p.update_iterations = 1;
	p.merge_landmarks_after_matches = matches;
	return p;
}

TEST(LandmarkMerge, TwoLandmarksOfPointsTheSensorCannotResolveBecomeOneAfterTheirMatches)
{
	LandmarkEkf ekf(jcbbMergingAfter(5));
	const StepReport first = ekf.processStep(standingBesideTwoUnresolvedPoints(0));
	ASSERT_EQ(first.associations.size(), 2u);
	ASSERT_EQ(first.associations[0].kind, Association::Kind::New);
	ASSERT_EQ(first.associations[1].kind, Association::Kind::New);
	// Each landmark matched once per step: four matches each is not enough.
	for (std::size_t k = 1; k <= 4; ++k) ekf.processStep(standingBesideTwoUnresolvedPoints(k));
	EXPECT_EQ(ekf.core().landmarkCount(), 2u);
	EXPECT_EQ(ekf.landmarkMerges(), 0u);
	// The fifth: their difference (0.15 m) within 1 sigma of its
	// uncertainty (about 0.17 m along the range after six sightings each).
	ekf.processStep(standingBesideTwoUnresolvedPoints(5));
	ASSERT_EQ(ekf.core().landmarkCount(), 1u);
	EXPECT_EQ(ekf.landmarkMerges(), 1u);
	const LandmarkId kept = ekf.ids().front();
	const LandmarkId dropped = first.associations[0].id == kept ? first.associations[1].id : first.associations[0].id;
	EXPECT_EQ(ekf.finalId(dropped), kept);
	// Both points seen again: the merged landmark takes both sightings
	// (it stands for two), rather than JCBB leaving one out or new.
	const StepReport after = ekf.processStep(standingBesideTwoUnresolvedPoints(6));
	for (const auto& a : after.associations)
	{
		EXPECT_EQ(a.kind, Association::Kind::Matched);
		EXPECT_EQ(a.id, kept);
	}
	EXPECT_EQ(ekf.core().landmarkCount(), 1u);
	// Between the two points, each fused about equally often; 3 sigma of
	// the merged estimate (0.3 m / sqrt(14 sightings) = 0.08 m).
	EXPECT_NEAR(ekf.core().landmark(0).x(), 3.075, 0.24);
	EXPECT_NEAR(ekf.core().landmark(0).y(), 0.0, 0.05);
}

TEST(LandmarkMerge, LandmarksNamedBySensorIdsAreNeverMerged)
{
	// The first scan carries IDs (association auto: by ID), the later ones
	// do not (by distance): the two landmarks are matched as often as
	// above, but their IDs are the sensor's.
	EkfAssociationParams params = jcbbMergingAfter(5);
	params.association = EkfAssociation::Auto;
	LandmarkEkf ekf(params);
	StepInput named = standingBesideTwoUnresolvedPoints(0);
	named.scan->measurements[0].id = 40;
	named.scan->measurements[1].id = 41;
	ekf.processStep(named);
	for (std::size_t k = 1; k <= 6; ++k) ekf.processStep(standingBesideTwoUnresolvedPoints(k));
	EXPECT_EQ(ekf.core().landmarkCount(), 2u);
	EXPECT_EQ(ekf.landmarkMerges(), 0u);
	EXPECT_TRUE(ekf.indexOf(40) && ekf.indexOf(41));
}

TEST(LandmarkMerge, WithoutMergingTheTwoLandmarksStayApart)
{
	LandmarkEkf ekf(jcbbMergingAfter(0));
	for (std::size_t k = 0; k <= 6; ++k) ekf.processStep(standingBesideTwoUnresolvedPoints(k));
	EXPECT_EQ(ekf.core().landmarkCount(), 2u);
	EXPECT_EQ(ekf.landmarkMerges(), 0u);
}

}  // namespace
