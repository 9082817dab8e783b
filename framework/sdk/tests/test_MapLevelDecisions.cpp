// The three outcomes of a local map's features against the global map
// (MapLevelDecisions.h) on a constructed map: features that are global
// ones are matched, one far from every candidate is new, and one between
// the gates, too close to a candidate to be new yet not it, is left out;
// "too close" judged against each candidate alone or given the accepted
// pairs; and a match another candidate, standing apart, explains as well
// given the other pairs is left out (ambiguity_margin_chi2_quantile).

#include <esif/localmap/LandmarkIdAllocator.h>
#include <esif/localmap/MapLevelDecisions.h>

#include <gtest/gtest.h>

#include <cmath>

#include <set>

namespace
{
using namespace esif;

/// Candidates on a 5 m grid with 0.1 m sigma; observed points with 0.1 m sigma.
PointSets grid(const std::vector<Eigen::Vector2d>& observed)
{
	PointSets s;
	const std::vector<Eigen::Vector2d> candidates = {{0, 0}, {5, 0}, {0, 5}, {5, 5}};
	s.candidates.resize(static_cast<Eigen::Index>(candidates.size()), 2);
	for (std::size_t c = 0; c < candidates.size(); ++c) s.candidates.row(static_cast<Eigen::Index>(c)) = candidates[c].transpose();
	s.candidates_cov = 0.01 * Eigen::MatrixXd::Identity(2 * s.candidates.rows(), 2 * s.candidates.rows());
	s.observed.resize(static_cast<Eigen::Index>(observed.size()), 2);
	for (std::size_t i = 0; i < observed.size(); ++i) s.observed.row(static_cast<Eigen::Index>(i)) = observed[i].transpose();
	s.observed_cov = 0.01 * Eigen::MatrixXd::Identity(2 * s.observed.rows(), 2 * s.observed.rows());
	return s;
}

TEST(MapLevelDecisions, MatchedNewAndPoorlyObserved)
{
	// Pair sigma 0.14 m per axis. Gates (2 dof): 0.99 -> d2 9.21 (0.43 m),
	// 0.9999 -> 18.4 (0.61 m).
	const auto d = decideMapFeatures(grid({{0.05, 0.0},	 // candidate 0, d2 0.125: matched
										   {5.0, 0.1},	// candidate 1: matched
										   {20, 20},  // far from all: new
										   {0.0, 5.5}}),  // 0.5 m from candidate 2, d2 12.5: neither
									 MapLevelAssociationParams{});
	ASSERT_EQ(d.outcome.size(), 4u);
	EXPECT_EQ(d.outcome[0], MapFeatureOutcome::Matched);
	EXPECT_EQ(d.candidate_of[0], 0);
	EXPECT_EQ(d.outcome[1], MapFeatureOutcome::Matched);
	EXPECT_EQ(d.candidate_of[1], 1);
	EXPECT_EQ(d.outcome[2], MapFeatureOutcome::New);
	EXPECT_EQ(d.outcome[3], MapFeatureOutcome::PoorlyObserved);
}

TEST(MapLevelDecisions, AJointlyIncompatibleShiftIsNotMatched)
{
	// Every feature shifted by 0.3 m the same way: each pair passes its
	// individual gate (d2 4.5), and JCBB keeps the largest jointly
	// compatible set, which a common shift passes too (the sets are
	// independent, so the joint test sums the pairs: 4 x 4.5 = 18 < chi2_8(0.99) = 20.1).
	// Shifted 0.4 m (d2 8 each, 32 in all) it fails jointly: JCBB's joint
	// tests never let all four pairs in (none is dropped afterwards).
	const auto shifted = [](double dx) {
		return grid({{dx, 0}, {5 + dx, 0}, {dx, 5}, {5 + dx, 5}});
	};
	const auto near = decideMapFeatures(shifted(0.3), MapLevelAssociationParams{});
	for (auto o : near.outcome) EXPECT_EQ(o, MapFeatureOutcome::Matched);
	const auto far = decideMapFeatures(shifted(0.4), MapLevelAssociationParams{});
	EXPECT_EQ(far.pairs_dropped, 0u);
	EXPECT_LT(std::count(far.outcome.begin(), far.outcome.end(), MapFeatureOutcome::Matched), 4);
}

TEST(MapLevelDecisions, ASightingNearAFeatureIsNewOnceThePairsPinThePlacement)
{
	// Candidates sharing a 2 m placement error (a local map placed from an
	// uncertain start pose): three features matched with a common 1.1 m
	// shift, and one 1.5 m beside the fourth candidate. Alone it lies at d2
	// 1.6 from that candidate, inside the new-feature gate (18.4): left out
	// as poorly observed. Given the shift the three pairs fix it is 1.5 m
	// off at 0.15 m sigma: new.
	PointSets s = grid({{1.0, 0.5}, {6.0, 0.5}, {1.0, 5.5}, {7.5, 5.5}});
	Eigen::MatrixXd common = Eigen::MatrixXd::Zero(8, 2);
	for (int c = 0; c < 4; ++c) common.block<2, 2>(2 * c, 0) = Eigen::Matrix2d::Identity();
	s.candidates_cov += 4.0 * common * common.transpose();
	MapLevelAssociationParams given_pairs;
	given_pairs.new_feature_test = NewFeatureTest::GivenPairs;
	const auto alone = decideMapFeatures(s, MapLevelAssociationParams{});
	const auto given = decideMapFeatures(s, given_pairs);
	ASSERT_EQ(given.outcome.size(), 4u);
	for (int i = 0; i < 3; ++i)
	{
		EXPECT_EQ(given.outcome[i], MapFeatureOutcome::Matched);
		EXPECT_EQ(given.candidate_of[i], i);
		EXPECT_EQ(alone.outcome[i], MapFeatureOutcome::Matched);
	}
	EXPECT_EQ(alone.outcome[3], MapFeatureOutcome::PoorlyObserved);
	EXPECT_EQ(given.outcome[3], MapFeatureOutcome::New);
}
/// Candidates at `candidates` with 0.05 m sigma; observed points with
/// sigma `observed_sd` each, independent.
PointSets points(const std::vector<Eigen::Vector2d>& candidates, const std::vector<Eigen::Vector2d>& observed,
				 const std::vector<double>& observed_sd)
{
	PointSets s;
	s.candidates.resize(static_cast<Eigen::Index>(candidates.size()), 2);
	for (std::size_t c = 0; c < candidates.size(); ++c) s.candidates.row(static_cast<Eigen::Index>(c)) = candidates[c].transpose();
	s.candidates_cov = 0.0025 * Eigen::MatrixXd::Identity(2 * s.candidates.rows(), 2 * s.candidates.rows());
	s.observed.resize(static_cast<Eigen::Index>(observed.size()), 2);
	s.observed_cov = Eigen::MatrixXd::Zero(2 * s.observed.rows(), 2 * s.observed.rows());
	for (std::size_t i = 0; i < observed.size(); ++i)
	{
		s.observed.row(static_cast<Eigen::Index>(i)) = observed[i].transpose();
		s.observed_cov.block<2, 2>(2 * i, 2 * i) = observed_sd[i] * observed_sd[i] * Eigen::Matrix2d::Identity();
	}
	return s;
}

MapLevelAssociationParams withAmbiguityMargin()
{
	MapLevelAssociationParams p;
	p.ambiguity_margin_chi2_quantile = 0.99;  // margin d2 9.21 (2 dof), as configs/mrclam/ uses
	return p;
}

TEST(MapLevelDecisions, AFeatureTwoSeparateCandidatesExplainAlikeIsLeftOut)
{
	// Feature 1 (0.25 m sigma) halfway between candidates 0 and 1, 1 m
	// apart: d2 3.85 to each, both inside the 0.99 gate (9.21), so JCBB
	// pairs it with one of them, a coin toss. Given the other pair
	// (feature 0 on candidate 2, independent of it) nothing changes, and
	// the two candidates stand 1 m apart, d2 15.4 in the pair's own
	// covariance: beyond the margin, a wrong pick moves the map by 1 m.
	const PointSets s = points({{0, 0}, {1, 0}, {5, 5}}, {{5, 5}, {0.5, 0}}, {0.1, 0.25});
	const auto plain = decideMapFeatures(s, MapLevelAssociationParams{});
	EXPECT_EQ(plain.outcome[1], MapFeatureOutcome::Matched);
	const auto careful = decideMapFeatures(s, withAmbiguityMargin());
	EXPECT_EQ(careful.outcome[0], MapFeatureOutcome::Matched);
	EXPECT_EQ(careful.candidate_of[0], 2);
	EXPECT_EQ(careful.outcome[1], MapFeatureOutcome::PoorlyObserved);
	EXPECT_EQ(careful.candidate_of[1], -1);
}

TEST(MapLevelDecisions, TwinCandidatesAreNoAmbiguity)
{
	// The same feature between candidates 0.2 m apart (cylinders of one
	// cluster): d2 0.6 between them in the pair's covariance, under the
	// margin. Either pick moves the map alike, so it is matched.
	const PointSets s = points({{0, 0}, {0.2, 0}, {5, 5}}, {{5, 5}, {0.1, 0}}, {0.1, 0.25});
	const auto d = decideMapFeatures(s, withAmbiguityMargin());
	EXPECT_EQ(d.outcome[1], MapFeatureOutcome::Matched);
	EXPECT_TRUE(d.candidate_of[1] == 0 || d.candidate_of[1] == 1);
}

TEST(MapLevelDecisions, AFeatureTheOtherPairsPlaceIsNotAmbiguous)
{
	// A local map placed with a 0.25 m sigma error both its features share
	// (0.1 m each of their own). Alone, feature 1 at (0.6, 0) is d2 2.1
	// from candidate 1 and 4.8 from candidate 0, which stand d2 13 apart:
	// ambiguous. Feature 0 sits 0.5 m left of candidate 2; given that pair
	// the shared error is known, feature 1 lies at about (1.02, 0), d2 0.02
	// from candidate 1 and 45 from candidate 0: matched to candidate 1.
	PointSets s = points({{0, 0}, {1, 0}, {5, 5}}, {{4.5, 5}, {0.6, 0}}, {0.1, 0.1});
	Eigen::MatrixXd common(4, 2);
	common << 1, 0, 0, 1, 1, 0, 0, 1;
	s.observed_cov += 0.0625 * common * common.transpose();
	const auto d = decideMapFeatures(s, withAmbiguityMargin());
	EXPECT_EQ(d.outcome[0], MapFeatureOutcome::Matched);
	EXPECT_EQ(d.candidate_of[0], 2);
	EXPECT_EQ(d.outcome[1], MapFeatureOutcome::Matched);
	EXPECT_EQ(d.candidate_of[1], 1);
	// Alone (feature 0 not there), the same feature is left out.
	const PointSets alone = points({{0, 0}, {1, 0}, {5, 5}}, {{0.6, 0}}, {std::sqrt(0.01 + 0.0625)});
	EXPECT_EQ(decideMapFeatures(alone, withAmbiguityMargin()).outcome[0], MapFeatureOutcome::PoorlyObserved);
}
}  // namespace

namespace
{
TEST(MapLevelDecisions, AppliedToTheFeaturesThatWereAssociatedOnly)
{
	// Features 0 and 2 were associated (slots), 1 was known by its ID:
	// feature 0 matches candidate 1 (global 71), feature 2 is poorly observed.
	MapLevelDecisions result;
	result.outcome = {MapFeatureOutcome::Matched, MapFeatureOutcome::PoorlyObserved};
	result.candidate_of = {1, -1};
	result.pairs_dropped = 2;
	result.jcbb_nodes = 9;
	result.fell_back = true;
	StepReport decisions;
	decisions.associations = {
		{Association::Kind::New, 5}, {Association::Kind::Matched, 40}, {Association::Kind::New, 7}};
	MapAssociationTally tally;
	applyMapLevelDecisions(result, {0, 2}, {70, 71}, decisions, tally);
	EXPECT_EQ(decisions.associations[0].kind, Association::Kind::Matched);
	EXPECT_EQ(decisions.associations[0].id, 71);
	EXPECT_EQ(decisions.associations[1].id, 40);
	EXPECT_EQ(decisions.associations[2].kind, Association::Kind::Rejected);
	EXPECT_EQ(rejectedCount(decisions), 1u);
	EXPECT_EQ(tally.pairs_dropped, 2u);
	EXPECT_EQ(tally.jcbb_nodes, 9u);
	EXPECT_EQ(tally.jcbb_fallbacks, 1u);

	MapAssociationTally run;
	run += tally;
	run += tally;
	EXPECT_EQ(run.jcbb_nodes, 18u);
	std::vector<std::pair<std::string, double>> counters;
	run.appendCounters(counters);
	ASSERT_EQ(counters.size(), 7u);
	EXPECT_EQ(counters[4].first, "jcbb_nodes");
	EXPECT_EQ(counters[4].second, 18.0);
}

/// The candidates of a local map whose start heading is uncertain: each at
/// `candidates[c]` with 0.1 m sigma of its own and a heading sigma of
/// `heading_sigma` rad shared by all (the local map's frame turns them
/// together about its origin); the observed points with 0.1 m sigma.
PointSets turnedMap(const std::vector<Eigen::Vector2d>& observed, const std::vector<Eigen::Vector2d>& candidates,
					double heading_sigma)
{
	PointSets s = grid(observed);
	const auto N = static_cast<Eigen::Index>(candidates.size());
	s.candidates.resize(N, 2);
	Eigen::VectorXd turn(2 * N);  // d(candidates)/d(heading)
	for (Eigen::Index c = 0; c < N; ++c)
	{
		s.candidates.row(c) = candidates[c].transpose();
		turn.segment<2>(2 * c) << -candidates[c].y(), candidates[c].x();
	}
	s.candidates_cov = 0.01 * Eigen::MatrixXd::Identity(2 * N, 2 * N) + heading_sigma * heading_sigma * turn * turn.transpose();
	return s;
}

TEST(MapLevelDecisions, AnchorsRuleOutAPairThatOnlyATurnExplains)
{
	// Candidate 0 at (3, 0); anchors' features at (0, 3) and (-3, 0), each
	// observed where it is. The undecided point lies 0.35 rad round from
	// candidate 0 (1.05 m off): under a 0.2 rad heading sigma alone that is
	// d2 ~ 2.9, inside the 0.99 gate (9.2), so without the anchors it is
	// matched. The anchors, unturned, pin the heading to ~0.03 rad: given
	// them the pair adds d2 ~ 37, and the three pairs fail the joint test
	// (chi2 6 dof, 0.99: 16.8); with one anchor (~0.05 rad) d2 ~ 27
	// against 13.3 for 4 dof. JCBB keeps the two anchors.
	const Eigen::Vector2d turned(3 * std::cos(0.35), 3 * std::sin(0.35));
	const std::vector<Eigen::Vector2d> candidates = {{3, 0}, {0, 3}, {-3, 0}};
	const MapLevelAssociationParams params;

	const PointSets alone = turnedMap({turned}, {candidates[0]}, 0.2);
	EXPECT_EQ(decideMapFeatures(alone, params).outcome[0], MapFeatureOutcome::Matched);

	const PointSets anchored = turnedMap({turned, {0, 3}, {-3, 0}}, candidates, 0.2);
	const MapLevelDecisions d = decideMapFeaturesGivenAnchors(anchored, 1, 1, params);
	ASSERT_EQ(d.outcome.size(), 1u);  // the undecided point's only
	EXPECT_NE(d.outcome[0], MapFeatureOutcome::Matched);
	EXPECT_EQ(d.candidate_of[0], -1);

	// Where candidate 0 is, given the same anchors, it is matched.
	const PointSets right = turnedMap({{3.05, 0}, {0, 3}, {-3, 0}}, candidates, 0.2);
	const MapLevelDecisions r = decideMapFeaturesGivenAnchors(right, 1, 1, params);
	EXPECT_EQ(r.outcome[0], MapFeatureOutcome::Matched);
	EXPECT_EQ(r.candidate_of[0], 0);
}

TEST(MapLevelDecisions, APointOnAnAnchorsFeatureIsLeftOut)
{
	// The undecided point sits on the anchor's feature (its cluster twin):
	// the feature is the anchor's, so the point is neither matched to it nor new.
	const PointSets sets = turnedMap({{0.05, 3}, {0, 3}}, {{10, 0}, {0, 3}}, 0.0);
	const MapLevelDecisions d = decideMapFeaturesGivenAnchors(sets, 1, 1, MapLevelAssociationParams{});
	EXPECT_EQ(d.outcome[0], MapFeatureOutcome::PoorlyObserved);
	EXPECT_EQ(d.candidate_of[0], -1);
	// One anchor point but two anchor candidates: refused.
	EXPECT_THROW(decideMapFeaturesGivenAnchors(sets, 1, 0, MapLevelAssociationParams{}), std::invalid_argument);
}

TEST(LandmarkIdAllocator, KeepsAFreeProposedIdElseTheNextAboveEveryIdGiven)
{
	std::set<LandmarkId> used = {1, 2, 10};
	const auto taken = [&](LandmarkId id) { return used.count(id) > 0; };
	LandmarkIdAllocator ids;
	const auto give = [&](LandmarkId proposed) {
		const LandmarkId id = ids.allocate(proposed, taken);
		used.insert(id);
		return id;
	};
	EXPECT_EQ(give(7), 7);	 // free: kept
	EXPECT_EQ(give(7), 8);	 // taken: the next free above every ID given (7)
	EXPECT_EQ(give(-1), 9);	 // none proposed
	EXPECT_EQ(give(2), 11);	 // 10 is taken too
	EXPECT_EQ(give(40), 40);
	EXPECT_EQ(give(-1), 41);
}
}  // namespace
