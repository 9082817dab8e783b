// Tentative landmarks (TentativeFeatures) and waiting on an ambiguous match
// (Ambiguity.h), the SDK's shared pieces of association without IDs; and
// both in LandmarkEkf, on small constructed cases: two twins, a blind
// drive, a poorly observed feature; and the association of a local map's
// scans with the global map's features (EarlierFeatures) in the same cases.

#include <esif/association/Ambiguity.h>
#include <esif/association/Chi2.h>
#include <esif/association/TentativeFeatures.h>
#include <esif/ekf/EarlierFeatures.h>
#include <esif/ekf/LandmarkEkf.h>
#include <esif/localmap/LocalMapBuilder.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
using namespace esif;

const double kGate = chi2Quantile(0.999, 2);  // 13.8

TEST(TentativeFeatures, SecondAgreeingSightingConfirms)
{
	TentativeFeatures c(kGate, 50);
	const Eigen::Matrix2d cov = 0.01 * Eigen::Matrix2d::Identity();	 // 0.1 m sigma
	EXPECT_FALSE(c.confirm(7, {1.0, 2.0}, cov, 10));
	EXPECT_EQ(c.tentativeCount(), 1u);
	// 0.2 m apart with a combined sigma of 0.14 m per axis: d2 = 2, inside.
	EXPECT_TRUE(c.confirm(7, {1.2, 2.0}, cov, 11));
	EXPECT_EQ(c.tentativeCount(), 0u);
}

TEST(TentativeFeatures, DisagreeingSightingReplacesTheFirst)
{
	TentativeFeatures c(kGate, 50);
	const Eigen::Matrix2d cov = 0.01 * Eigen::Matrix2d::Identity();
	EXPECT_FALSE(c.confirm(7, {4.0, 2.0}, cov, 10));  // a misread: the neighbour's place, 3 m off
	EXPECT_FALSE(c.confirm(7, {1.0, 2.0}, cov, 11));  // d2 = 9 / 0.02 = 450: replaces it
	EXPECT_EQ(c.tentativeCount(), 1u);
	EXPECT_TRUE(c.confirm(7, {1.05, 2.0}, cov, 12));  // agrees with the replacement
}

TEST(TentativeFeatures, OtherIdsAndExpiredSightingsDoNotConfirm)
{
	TentativeFeatures c(kGate, 5);
	const Eigen::Matrix2d cov = 0.01 * Eigen::Matrix2d::Identity();
	EXPECT_FALSE(c.confirm(7, {1.0, 2.0}, cov, 10));
	EXPECT_FALSE(c.confirm(8, {1.0, 2.0}, cov, 11));  // same place, another landmark
	EXPECT_FALSE(c.confirm(7, {1.0, 2.0}, cov, 16));  // step 16 > 10 + 5: the first has expired
	EXPECT_TRUE(c.confirm(7, {1.0, 2.0}, cov, 17));
}

TEST(TentativeFeatures, WithoutIdsTheNearestAgreeingSightingConfirms)
{
	TentativeFeatures c(kGate, 50);
	const Eigen::Matrix2d cov = 0.01 * Eigen::Matrix2d::Identity();
	EXPECT_FALSE(c.confirm(std::nullopt, {0.0, 0.0}, cov, 1));	 // clutter
	EXPECT_FALSE(c.confirm(std::nullopt, {5.0, 0.0}, cov, 1));	 // a feature
	EXPECT_TRUE(c.confirm(std::nullopt, {5.1, 0.1}, cov, 2));
	EXPECT_EQ(c.tentativeCount(), 1u);	// the clutter waits, and expires
	EXPECT_FALSE(c.confirm(std::nullopt, {20.0, 0.0}, cov, 3));
	EXPECT_EQ(c.tentativeCount(), 2u);
}

TEST(Ambiguity, ARunnerUpWithinTheMarginMakesTheMatchWait)
{
	const double margin = ambiguityMarginDistance2(0.99);  // 9.21
	EXPECT_NEAR(margin, 9.21, 0.01);
	const auto resolvable = [](Eigen::Index) { return 100.0; };
	Eigen::VectorXd d2(3);
	d2 << 1.0, 5.0, 30.0;  // candidate 1 is e^-2 as likely as 0: not 100 times less
	EXPECT_TRUE(ambiguousMatch(d2, 0, margin, resolvable));
	d2 << 1.0, 11.0, 30.0;	// 11 - 1 >= 9.21: a likelihood ratio above 100
	EXPECT_FALSE(ambiguousMatch(d2, 0, margin, resolvable));
	EXPECT_FALSE(ambiguousMatch(d2, 0, 0.0, resolvable));  // off
}

TEST(Ambiguity, TwinsTheSensorCannotTellApartDoNotMakeItWait)
{
	Eigen::VectorXd d2(2);
	d2 << 1.0, 1.5;
	EXPECT_FALSE(ambiguousMatch(d2, 0, 9.21, [](Eigen::Index) { return 2.0; }));
	EXPECT_TRUE(ambiguousMatch(d2, 0, 9.21, [](Eigen::Index) { return 50.0; }));
}

/// A step driving `dx` forward with odometry noise `sigma_xy`, `sigma_phi`
/// per step, then seeing `points` (range, bearing) with a sensor of 0.1 m, 1 deg.
StepInput step(std::size_t k, double dx, double sigma_xy, double sigma_phi,
			   const std::vector<Eigen::Vector2d>& points)
{
	StepInput s;
	s.index = k;
	if (dx >= 0)
		s.odometry = OdometryIncrement{{dx, 0, 0}, Eigen::Vector3d(sigma_xy * sigma_xy, sigma_xy * sigma_xy, sigma_phi * sigma_phi).asDiagonal()};
	Scan scan;
	for (const auto& p : points)
	{
		RangeBearing m;
		m.range_m = p(0);
		m.bearing_rad = p(1);
		m.cov = Eigen::Vector2d(0.01, std::pow(M_PI / 180, 2)).asDiagonal();
		scan.measurements.push_back(m);
	}
	s.scan = scan;
	return s;
}

EkfAssociationParams distanceAssociation(bool confirm, double ambiguity)
{
	EkfAssociationParams p;
	p.association = EkfAssociation::NearestNeighbor;
	p.confirm_new_landmarks = confirm;
	p.ambiguity_margin_chi2_quantile = ambiguity;
	p.update_iterations = 1;
	return p;
}

TEST(LandmarkEkfTentative, ALandmarkEntersOnlyWhenASecondSightingConfirmsIt)
{
	LandmarkEkf ekf(distanceAssociation(true, 0));
	// First sighting of a landmark 5 m ahead: held, not mapped, not fused.
	auto r = ekf.processStep(step(0, -1, 0, 0, {{5.0, 0.0}}));
	EXPECT_EQ(r.associations[0].kind, Association::Kind::Rejected);
	EXPECT_EQ(ekf.core().landmarkCount(), 0u);
	// A clutter return 3 m to the left, seen once.
	r = ekf.processStep(step(1, 0.1, 0.01, 0.001, {{4.9, 0.0}, {3.0, M_PI / 2}}));
	EXPECT_EQ(r.associations[0].kind, Association::Kind::New);	// the second sighting confirms: mapped
	EXPECT_EQ(r.associations[1].kind, Association::Kind::Rejected);
	EXPECT_EQ(ekf.core().landmarkCount(), 1u);
	// The landmark is matched from now on; the clutter never enters the map.
	for (std::size_t k = 2; k < 60; ++k)
	{
		r = ekf.processStep(step(k, 0.0, 0.01, 0.001, {{4.9, 0.0}}));
		EXPECT_EQ(r.associations[0].kind, Association::Kind::Matched) << k;
	}
	EXPECT_EQ(ekf.core().landmarkCount(), 1u);
	EXPECT_EQ(ekf.tentativeCount(), 0u);  // the clutter's sighting expired
}

TEST(LandmarkEkfTentative, AnUnconfirmedSightingNeverMovesTheRobot)
{
	LandmarkEkf ekf(distanceAssociation(true, 0));
	ekf.processStep(step(0, -1, 0, 0, {{5.0, 0.0}}));
	ekf.processStep(step(1, 1.0, 0.1, 0.01, {{4.0, 0.0}}));	 // mapped here
	const Pose2 before = ekf.core().robot();
	// A poorly observed feature: one sighting, far from the mapped one.
	ekf.processStep(step(2, 0.0, 0.1, 0.01, {{3.9, 0.0}, {8.0, -1.0}}));
	const Pose2 after_single = ekf.core().robot();
	EkfAssociationParams plain = distanceAssociation(true, 0);
	LandmarkEkf reference(plain);
	reference.processStep(step(0, -1, 0, 0, {{5.0, 0.0}}));
	reference.processStep(step(1, 1.0, 0.1, 0.01, {{4.0, 0.0}}));
	reference.processStep(step(2, 0.0, 0.1, 0.01, {{3.9, 0.0}}));
	EXPECT_LT((after_single - reference.core().robot()).norm(), 1e-12);
	EXPECT_GT((after_single - before).norm(), 0.0);	 // the mapped landmark's update did move it
}

TEST(LandmarkEkfAmbiguity, AfterABlindDriveTheFirstMatchWaitsUntilUnambiguous)
{
	// Two landmarks 1.5 m apart, both mapped from the start.
	LandmarkEkf ekf(distanceAssociation(false, 0.99));
	ekf.processStep(step(0, -1, 0, 0, {{6.0, 0.25}, {6.0, 0.0}}));
	ASSERT_EQ(ekf.core().landmarkCount(), 2u);
	// A blind drive: 30 steps of odometry with large heading noise, no scan.
	for (std::size_t k = 1; k <= 30; ++k)
	{
		StepInput s;
		s.index = k;
		s.odometry = OdometryIncrement{{0.0, 0, 0}, Eigen::Vector3d(1e-4, 1e-4, std::pow(0.02, 2)).asDiagonal()};
		ekf.processStep(s);
	}
	// One landmark in view: compatible with both. It waits.
	auto r = ekf.processStep(step(31, 0.0, 0.001, 0.001, {{6.0, 0.0}}));
	EXPECT_EQ(r.associations[0].kind, Association::Kind::Rejected);
	EXPECT_EQ(ekf.ambiguousWaits(), 1u);
	// Both in view: JCBB pairs them jointly, the pose is resolved, and single
	// sightings are matched again.
	r = ekf.processStep(step(32, 0.0, 0.001, 0.001, {{6.0, 0.25}, {6.0, 0.0}}));
	EXPECT_EQ(r.associations[0].kind, Association::Kind::Matched);
	EXPECT_EQ(r.associations[1].kind, Association::Kind::Matched);
	r = ekf.processStep(step(33, 0.0, 0.001, 0.001, {{6.0, 0.0}}));
	EXPECT_EQ(r.associations[0].kind, Association::Kind::Matched);
	EXPECT_EQ(ekf.ambiguousWaits(), 1u);
}

TEST(LandmarkEkfAmbiguity, TwinsCloserThanTheSensorResolvesAreMatchedNotWaitedOn)
{
	// Two landmarks 0.2 m apart at 6 m: 1.9 deg of bearing, which a 1 deg
	// sensor separates by less than the 0.99 margin once range adds nothing.
	LandmarkEkf ekf(distanceAssociation(false, 0.99));
	ekf.processStep(step(0, -1, 0, 0, {{6.0, 0.0}}));
	// The twin: rejected as ambiguous with the first (not a new landmark).
	auto r = ekf.processStep(step(1, 0.0, 0.01, 0.001, {{6.0, 0.0333}}));
	EXPECT_NE(r.associations[0].kind, Association::Kind::New);
	EXPECT_EQ(ekf.core().landmarkCount(), 1u);
	EXPECT_EQ(ekf.ambiguousWaits(), 0u);
}

std::size_t rejectedIn(const StepReport& r)
{
	return static_cast<std::size_t>(std::count_if(r.associations.begin(), r.associations.end(),
		[](const Association& a) { return a.kind == Association::Kind::Rejected; }));
}

TEST(LandmarkEkfRejections, EverySightingLeftOutIsCountedByItsCause)
{
	// Held: the first sighting of a landmark waits for a second.
	LandmarkEkf held(distanceAssociation(true, 0));
	std::size_t rejected = rejectedIn(held.processStep(step(0, -1, 0, 0, {{5.0, 0.0}})));
	EXPECT_EQ(rejected, 1u);
	EXPECT_EQ(held.rejections().unconfirmed, 1u);

	// Poorly observed: 0.51 m beyond a landmark mapped from one sighting at
	// 5 m (range variance 0.01 + 0.01): d2 = 13, outside the 0.99 gate
	// (9.21), inside the 0.9999 new-landmark gate (18.4).
	LandmarkEkf poor(distanceAssociation(false, 0));
	poor.processStep(step(0, -1, 0, 0, {{5.0, 0.0}}));
	rejected = rejectedIn(poor.processStep(step(1, 0.0, 1e-4, 1e-5, {{5.51, 0.0}})));
	EXPECT_EQ(rejected, 1u);
	EXPECT_EQ(poor.rejections().poorly_observed, 1u);
	EXPECT_EQ(poor.core().landmarkCount(), 1u);

	// Each cause only where it applies.
	EXPECT_EQ(held.rejections().poorly_observed + held.rejections().ambiguous_waits, 0u);
	EXPECT_EQ(poor.rejections().unconfirmed + poor.rejections().ambiguous_waits, 0u);
}

TEST(LocalMapBuilderRejections, TheLocalMapsCountsAreSummedOverEveryMap)
{
	// Maps of two steps; each starts with a first sighting held for a second.
	LocalMapBuilderParams params;
	params.local_map_steps = 2;
	params.association = distanceAssociation(true, 0);
	LocalMapBuilder builder(params);
	std::size_t rejected = 0;
	for (std::size_t k = 0; k < 6; ++k)
		rejected += rejectedIn(builder.processStep(step(k, k ? 0.1 : -1.0, 1e-3, 1e-4, {{5.0 - 0.1 * k, 0.0}})));
	EXPECT_EQ(builder.openMapIndex(), 4u);  // three closed maps, one open
	EXPECT_EQ(builder.rejections().unconfirmed, rejected);
	EXPECT_GE(rejected, 3u);
}

/// `s` with every measurement's fused noise inflated to 0.5 m, 3 deg (errors
/// that repeat over sightings, as calibrated on MRCLAM) and, with `sighting`,
/// the noise of one sighting alone at 0.1 m, 0.5 deg.
StepInput withInflatedNoise(StepInput s, bool sighting)
{
	for (auto& m : s.scan->measurements) m.cov = Eigen::Vector2d(0.25, std::pow(3 * M_PI / 180, 2)).asDiagonal();
	if (sighting) s.scan->sighting_cov = Eigen::Vector2d(0.01, std::pow(0.5 * M_PI / 180, 2)).asDiagonal();
	return s;
}

/// The kind of association a cylinder 0.8 m beside one seen 16 times from
/// the same pose gets, 6 m ahead; measurements nearer than `min_range_m`
/// are left out (none is).
Association::Kind neighbourBesideAWellMappedLandmark(bool sighting, double min_range_m = 0)
{
	EkfAssociationParams params = distanceAssociation(false, 0);
	params.min_range_m = min_range_m;
	LandmarkEkf ekf(params);
	for (std::size_t k = 0; k < 16; ++k)
		ekf.processStep(withInflatedNoise(step(k, k ? 0.0 : -1.0, 1e-3, 1e-4, {{6.0, 0.0}}), sighting));
	const Eigen::Vector2d neighbour(std::hypot(6.0, 0.8), std::atan2(0.8, 6.0));
	const auto r = ekf.processStep(withInflatedNoise(step(16, 0.0, 1e-3, 1e-4, {neighbour}), sighting));
	return r.associations.at(0).kind;
}

TEST(LandmarkEkfSightingNoise, ANeighbourBeyondOneSightingsNoiseIsNewNotMerged)
{
	// The landmark's lateral sigma after 16 fused sightings: 6 m x 3 deg / 4 =
	// 0.08 m. Against the inflated noise (0.31 m lateral at 6 m) the neighbour
	// 0.8 m off is at d2 = 0.64 / (0.08^2 + 0.31^2) = 6.2, inside the 0.99
	// gate (9.2): merged. Against one sighting's noise (0.05 m lateral),
	// d2 = 0.64 / (0.08^2 + 0.05^2) = 72, beyond the new-landmark gate (18.4).
	EXPECT_EQ(neighbourBesideAWellMappedLandmark(false), Association::Kind::Matched);
	EXPECT_EQ(neighbourBesideAWellMappedLandmark(true), Association::Kind::New);
}

TEST(LandmarkEkfSightingNoise, AMinimumRangeKeepsTheSightingNoise)
{
	// Leaving out measurements nearer than min_range_m (none here: all are
	// 6 m away) must not change the noise the gates use: the usable part of
	// the scan once lost its sighting noise, and the neighbour was merged.
	EXPECT_EQ(neighbourBesideAWellMappedLandmark(true, 0.3), Association::Kind::New);
}

TEST(LandmarkEkfSightingNoise, FusionKeepsTheInflatedNoise)
{
	// The sighting noise decides associations only: the same matches fuse
	// to the same estimate with or without it.
	LandmarkEkf inflated(distanceAssociation(false, 0)), both(distanceAssociation(false, 0));
	for (std::size_t k = 0; k < 5; ++k)
	{
		const StepInput s = step(k, k ? 0.1 : -1.0, 1e-2, 1e-3, {{6.0 - 0.1 * k, 0.01 * k}});
		inflated.processStep(withInflatedNoise(s, false));
		both.processStep(withInflatedNoise(s, true));
	}
	EXPECT_EQ(inflated.core().state(), both.core().state());
	EXPECT_EQ(inflated.core().covariance(), both.core().covariance());
}

TEST(EarlierFeatures, InFrameMovesTheFeaturesAndAddsTheFrameUncertainty)
{
	EarlierFeatures f;
	f.ids = {7};
	f.positions = Eigen::Vector2d(2.0, 0.0);
	f.covariance = Eigen::Vector2d(0.04, 0.01).asDiagonal();
	// Seen from (1, 0) facing +y, whose heading is uncertain by 0.1 rad: the
	// feature is 1 m to its right, and the heading moves it along the
	// frame's x axis by 1 m x 0.1 rad.
	const EarlierFeatures g = f.inFrame(Pose2(1.0, 0.0, M_PI / 2), Eigen::Vector3d(0, 0, 0.01).asDiagonal());
	ASSERT_EQ(g.ids, f.ids);
	EXPECT_NEAR(g.position(0).x(), 0.0, 1e-12);
	EXPECT_NEAR(g.position(0).y(), -1.0, 1e-12);
	// The feature's own covariance rotated by 90 deg (x <-> y), plus 0.01 in x.
	EXPECT_NEAR(g.covariance(0, 0), 0.01 + 0.01, 1e-12);
	EXPECT_NEAR(g.covariance(1, 1), 0.04, 1e-12);
	EXPECT_NEAR(g.covariance(0, 1), 0.0, 1e-12);
}

/// Earlier features `points` (IDs 100, 101, ...) seen from the global
/// frame's origin, uncertain by `sigma_xy` each and by a shared heading of
/// `sigma_phi` (the start pose's, correlating them).
EarlierFeatures earlierAtOrigin(const std::vector<Eigen::Vector2d>& points, double sigma_xy, double sigma_phi)
{
	const auto n = static_cast<Eigen::Index>(points.size());
	Eigen::MatrixXd joint = std::pow(sigma_xy, 2) * Eigen::MatrixXd::Identity(3 + 2 * n, 3 + 2 * n);
	joint(0, 0) = joint(1, 1) = 0;
	joint(2, 2) = sigma_phi * sigma_phi;
	std::vector<LandmarkId> ids;
	for (Eigen::Index i = 0; i < n; ++i) ids.push_back(100 + i);
	return earlierFeaturesInFrame(Pose2::Zero(), ids, points, joint);
}

/// A builder of one open map (no close) associating by distance, given the
/// earlier features `earlier` before its first step.
LocalMapBuilder builderWithEarlier(const EarlierFeatures& earlier, EkfAssociationParams association)
{
	LocalMapBuilderParams params;
	params.local_map_steps = 0;
	params.association = association;
	LocalMapBuilder builder(params);
	builder.reserveIdsUpTo(999);
	builder.setEarlierFeatures(earlier);
	return builder;
}

TEST(LocalMapBuilderEarlierFeatures, ASightingOfOneStartsItsFeatureUnderItsId)
{
	LocalMapBuilder builder = builderWithEarlier(earlierAtOrigin({{5.0, 0.0}, {0.0, 5.0}}, 0.1, 0.0),
												 distanceAssociation(false, 0));
	// 5.05 m ahead: d2 = 0.0025 / (0.01 + 0.01) = 0.125, inside the gate.
	auto r = builder.processStep(step(0, -1, 0, 0, {{5.05, 0.0}, {8.0, -1.0}}));
	ASSERT_EQ(r.associations.size(), 2u);
	EXPECT_EQ(r.associations[0].kind, Association::Kind::New);
	EXPECT_EQ(r.associations[0].id, 100);
	EXPECT_EQ(r.associations[1].kind, Association::Kind::New);	// far from both: the builder's own number
	EXPECT_EQ(r.associations[1].id, 1000);
	EXPECT_EQ(builder.earlierFeatureStarts(), 1u);
	// The open map places it by the measurement alone and knows nothing of
	// the global map: its state is what a filter given the IDs alone holds.
	const LandmarkEkf& open = builder.openMap();
	ASSERT_EQ(open.ids(), (std::vector<LandmarkId>{100, 1000}));
	EXPECT_NEAR(open.core().landmark(0).x(), 5.05, 1e-12);
	EkfAssociationParams by_ids = distanceAssociation(false, 0);
	by_ids.association = EkfAssociation::KnownIds;
	LandmarkEkf alone(by_ids);
	StepInput with_ids = step(0, -1, 0, 0, {{5.05, 0.0}, {8.0, -1.0}});
	with_ids.scan->measurements[0].id = 100;
	with_ids.scan->measurements[1].id = 1000;
	alone.processStep(with_ids);
	EXPECT_LT((open.core().covariance() - alone.core().covariance()).norm(), 1e-12);
	// From now on a sighting of it is a match in the open map.
	r = builder.processStep(step(1, 0.0, 1e-3, 1e-4, {{5.0, 0.0}}));
	EXPECT_EQ(r.associations[0].kind, Association::Kind::Matched);
	EXPECT_EQ(r.associations[0].id, 100);
	EXPECT_EQ(builder.earlierFeatureStarts(), 1u);
}

TEST(LocalMapBuilderEarlierFeatures, ASightingBesideOneIsLeftOutNotMappedAgain)
{
	// As the poorly observed landmark above: 0.51 m beyond an earlier feature
	// known to 0.1 m, d2 = 13, outside the 0.99 gate and inside the 0.9999
	// new-landmark gate.
	LocalMapBuilder builder =
		builderWithEarlier(earlierAtOrigin({{5.0, 0.0}}, 0.1, 0.0), distanceAssociation(false, 0));
	const auto r = builder.processStep(step(0, -1, 0, 0, {{5.51, 0.0}}));
	EXPECT_EQ(r.associations[0].kind, Association::Kind::Rejected);
	EXPECT_EQ(builder.rejections().poorly_observed, 1u);
	EXPECT_EQ(builder.openMap().core().landmarkCount(), 0u);
}

TEST(LocalMapBuilderEarlierFeatures, TwinsUnderAnUncertainStartHeadingWaitThenAMatchSettlesTheHeading)
{
	// Two earlier features 1.5 m apart, 6 m ahead; the map's start heading is
	// uncertain by 0.2 rad (a blind drive): 1.2 m across at 6 m, so one
	// sighting fits both.
	EkfAssociationParams jcbb = distanceAssociation(false, 0.99);
	jcbb.association = EkfAssociation::Jcbb;
	LocalMapBuilder builder = builderWithEarlier(earlierAtOrigin({{6.0, 0.0}, {6.0, 1.5}}, 0.05, 0.2), jcbb);
	auto r = builder.processStep(step(0, -1, 0, 0, {{6.0, 0.1}}));
	EXPECT_EQ(r.associations[0].kind, Association::Kind::Rejected);
	EXPECT_EQ(builder.rejections().ambiguous_waits, 1u);
	EXPECT_EQ(builder.openMap().core().landmarkCount(), 0u);
	// Both together: their 1.5 m spacing, which the heading does not blur,
	// decides the pairing jointly, each under its own ID.
	const Eigen::Vector2d left(std::hypot(6.0, 1.5), std::atan2(1.5, 6.0));
	r = builder.processStep(step(1, 0.0, 1e-3, 1e-4, {{6.0, 0.1}, left + Eigen::Vector2d(0, 0.1)}));
	EXPECT_EQ(r.associations[0].kind, Association::Kind::New);
	EXPECT_EQ(r.associations[0].id, 100);
	EXPECT_EQ(r.associations[1].kind, Association::Kind::New);
	EXPECT_EQ(r.associations[1].id, 101);
	// The association filter now knows the heading (0.1 rad off): a lone
	// sighting of the right twin, which waited at step 0, is matched.
	r = builder.processStep(step(2, 0.0, 1e-3, 1e-4, {left + Eigen::Vector2d(0, 0.1)}));
	EXPECT_EQ(r.associations[0].kind, Association::Kind::Matched);
	EXPECT_EQ(r.associations[0].id, 101);
	EXPECT_EQ(builder.rejections().ambiguous_waits, 1u);
}

TEST(LocalMapBuilderEarlierFeatures, WithAnOdometryLinkTheyAreMovedThroughTheLink)
{
	// Maps of one step linked by the next step's odometry (eq. 5.4): the
	// earlier features, given in the previous map's end frame, are seen from
	// the new map's origin one link later (1 m ahead, 0.05 m uncertain).
	LocalMapBuilderParams params;
	params.local_map_steps = 1;
	params.local_map_link = LocalMapLink::Odometry;
	params.association = distanceAssociation(false, 0);
	LocalMapBuilder builder(params);
	builder.reserveIdsUpTo(999);
	builder.processStep(step(0, -1, 0, 0, {}));
	ASSERT_TRUE(builder.takeClosedMap());
	builder.setEarlierFeatures(earlierAtOrigin({{5.0, 0.0}}, 0.05, 0.0));
	// The feature 4 m ahead of the new origin: its earlier ID. Unmoved, it
	// would sit 1 m off, d2 = 1 / (0.0025 + 0.01) = 80: a new feature.
	const auto r = builder.processStep(step(1, 1.0, 0.05, 1e-4, {{4.0, 0.0}}));
	ASSERT_EQ(r.associations.size(), 1u);
	EXPECT_EQ(r.associations[0].kind, Association::Kind::New);
	EXPECT_EQ(r.associations[0].id, 100);
}

TEST(LocalMapBuilderEarlierFeatures, WithNoneInTheRadiusTheCloseRenamesNothing)
{
	// Maps of one step, the robot standing still. The first map starts the
	// feature 5 m ahead under its own number. The joining filter then finds
	// no global feature within the radius of the second map's start and gives
	// none: the second map's sighting of the same place is its own feature,
	// left to the map level, and not renamed to the previous map's by the
	// close (which it would be without the association filter).
	LocalMapBuilderParams params;
	params.local_map_steps = 1;
	params.association = distanceAssociation(false, 0);
	LocalMapBuilder builder(params);
	builder.reserveIdsUpTo(999);
	builder.processStep(step(0, -1, 0, 0, {{5.0, 0.0}}));
	const auto first = builder.takeClosedMap();
	ASSERT_TRUE(first);
	ASSERT_EQ(first->features.size(), 1u);
	EXPECT_EQ(first->features[0].id, 1000);

	builder.setEarlierFeatures(EarlierFeatures{});
	builder.processStep(step(1, 0.0, 1e-3, 1e-4, {{5.0, 0.0}}));
	const auto second = builder.takeClosedMap();
	ASSERT_TRUE(second);
	ASSERT_EQ(second->features.size(), 1u);
	EXPECT_EQ(second->features[0].id, 1001);
	EXPECT_FALSE(second->features[0].in_earlier_maps);
}
}  // namespace
