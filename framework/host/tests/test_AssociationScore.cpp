// A final map's landmarks identified with true landmarks, and the scores
// built on them (found, duplicated, spurious, precision, recall), on small
// hand-made cases whose every count is worked out in the comments.

#include <esif/eval/AssociationAudit.h>
#include <esif/eval/AssociationScore.h>
#include <esif/eval/LandmarkIdentities.h>

#include <gtest/gtest.h>

namespace
{
using namespace esif;
using K = Association::Kind;
constexpr LandmarkId A = 10, B = 20, C = 30;
const std::optional<LandmarkId> kClutter = std::nullopt;

/// Every counted kind of landmark and error at once (filter landmarks 0-4,
/// true landmarks A, B, C):
///  step 0: A -> new 0; B -> new 1; clutter -> new 2 (spurious);
///  step 1: A -> matched 0; A -> new 3 (a duplicate of A); C -> rejected;
///  step 2: B -> matched 0 (a wrong match); C -> rejected; clutter -> rejected.
/// Landmark 4 of the final map was never given a measurement.
AssociationAudit mixedAudit()
{
	AssociationAudit audit;
	audit.record({{{K::New, 0}, {K::New, 1}, {K::New, 2}}}, {A, B, kClutter});
	audit.record({{{K::Matched, 0}, {K::New, 3}, {K::Rejected, -1}}}, {A, A, C});
	audit.record({{{K::Matched, 0}, {K::Rejected, -1}, {K::Rejected, -1}}}, {B, C, kClutter});
	return audit;
}

std::vector<LandmarkEstimate> mapOf(const std::vector<LandmarkId>& ids)
{
	std::vector<LandmarkEstimate> map;
	for (const LandmarkId id : ids) map.push_back({id, {0, 0}, Eigen::Matrix2d::Identity()});
	return map;
}

TEST(LandmarkIdentities, MajorityOfEachLandmarksMeasurements)
{
	const AssociationAudit audit = mixedAudit();
	const LandmarkIdentities ids = landmarkIdentities(audit, mapOf({0, 1, 2, 3, 4}));
	EXPECT_TRUE(ids.truth);
	ASSERT_EQ(ids.landmarks.size(), 5u);
	// Landmark 0: A twice, B once -> A with 2 of its 3 measurements.
	EXPECT_EQ(ids.landmarks[0].true_id, A);
	EXPECT_EQ(ids.landmarks[0].votes, 2u);
	EXPECT_EQ(ids.landmarks[0].measurements, 3u);
	EXPECT_EQ(ids.landmarks[1].true_id, B);
	// Clutter only: used once, no identity.
	EXPECT_FALSE(ids.landmarks[2].true_id);
	EXPECT_EQ(ids.landmarks[2].measurements, 1u);
	EXPECT_EQ(ids.landmarks[3].true_id, A);
	EXPECT_EQ(ids.landmarks[3].votes, 1u);
	// Never measured.
	EXPECT_FALSE(ids.landmarks[4].true_id);
	EXPECT_EQ(ids.landmarks[4].measurements, 0u);
	// A is stood for by landmark 0 (2 votes against landmark 3's 1).
	const auto primary = primaryLandmarks(ids);
	EXPECT_EQ(primary.size(), 2u);
	EXPECT_EQ(primary.at(A), 0);
	EXPECT_EQ(primary.at(B), 1);
}

TEST(LandmarkIdentities, TiedDuplicatesLeaveTheLowestLandmarkStanding)
{
	AssociationAudit audit;
	audit.record({{{K::New, 8}, {K::New, 5}}}, {A, A});
	EXPECT_EQ(primaryLandmarks(landmarkIdentities(audit, mapOf({8, 5}))).at(A), 5);
}

TEST(AssociationScore, CountsLandmarksAndScoresEveryMeasurement)
{
	const AssociationAudit audit = mixedAudit();
	const auto score = scoreAssociations(landmarkIdentities(audit, mapOf({0, 1, 2, 3, 4})), audit);
	ASSERT_TRUE(score);
	EXPECT_EQ(score->true_landmarks, 3u);  // A, B and C (C only rejected)
	EXPECT_EQ(score->found, 2u);  // A and B
	EXPECT_EQ(score->duplicated, 1u);  // landmark 3
	EXPECT_EQ(score->spurious, 2u);	 // landmark 2 (clutter) and 4 (no measurement)
	// Used: 4 new + 2 matched. Correct: the two A on landmark 0 and the B on
	// landmark 1; the B matched to 0, the A on the duplicate and the clutter
	// on landmark 2 are not.
	EXPECT_EQ(score->used, 6u);
	EXPECT_EQ(score->correct, 3u);
	EXPECT_EQ(score->with_truth, 7u);  // all but the two clutter returns
	EXPECT_DOUBLE_EQ(*score->precision, 3.0 / 6.0);
	EXPECT_DOUBLE_EQ(*score->recall, 3.0 / 7.0);
	// The existing count agrees: one B on landmark 0, one duplicate of A.
	EXPECT_EQ(audit.wrongCount(), 2u);
}

TEST(AssociationScore, LandmarksTheFinalMapDroppedHoldNoCorrectMeasurement)
{
	// Landmark 3 (A's duplicate) is not in the final map: its measurement
	// still counts as used, on no landmark that stands for A.
	const AssociationAudit audit = mixedAudit();
	const auto score = scoreAssociations(landmarkIdentities(audit, mapOf({0, 1, 2})), audit);
	EXPECT_EQ(score->duplicated, 0u);
	EXPECT_EQ(score->spurious, 1u);
	EXPECT_EQ(score->correct, 3u);
	EXPECT_DOUBLE_EQ(*score->precision, 3.0 / 6.0);
}

TEST(AssociationScore, IdsShownArePerfectButForRejections)
{
	// A filter given the IDs: every landmark is its true one; one measurement
	// of the ten rejected by an ID gate costs recall only.
	AssociationAudit audit;
	audit.record({{{K::New, A}, {K::New, B}}}, {A, B});
	for (int k = 0; k < 3; ++k) audit.record({{{K::Matched, A}, {K::Matched, B}}}, {A, B});
	audit.record({{{K::Matched, A}, {K::Rejected, -1}}}, {A, B});
	const auto score = scoreAssociations(landmarkIdentities(audit, mapOf({A, B})), audit);
	EXPECT_EQ(score->true_landmarks, 2u);
	EXPECT_EQ(score->found, 2u);
	EXPECT_EQ(score->duplicated + score->spurious, 0u);
	EXPECT_DOUBLE_EQ(*score->precision, 1.0);
	EXPECT_DOUBLE_EQ(*score->recall, 9.0 / 10.0);
}

TEST(AssociationScore, ReCreatingEveryLandmarkScoresNearZero)
{
	// Every sighting starts a new landmark: each copy is "identified", but
	// only one per true landmark stands for it.
	AssociationAudit audit;
	for (LandmarkId k = 0; k < 10; ++k) audit.record({{{K::New, 2 * k}, {K::New, 2 * k + 1}}}, {A, B});
	std::vector<LandmarkId> ids;
	for (LandmarkId k = 0; k < 20; ++k) ids.push_back(k);
	const auto score = scoreAssociations(landmarkIdentities(audit, mapOf(ids)), audit);
	EXPECT_EQ(score->found, 2u);
	EXPECT_EQ(score->duplicated, 18u);
	EXPECT_DOUBLE_EQ(*score->precision, 2.0 / 20.0);
	EXPECT_DOUBLE_EQ(*score->recall, 2.0 / 20.0);
}

TEST(AssociationScore, NoneWithoutTruthAndNullKeys)
{
	AssociationAudit audit;
	audit.record({{{K::New, 0}, {K::Matched, 0}}}, {kClutter, kClutter});
	const LandmarkIdentities ids = landmarkIdentities(audit, mapOf({0}));
	EXPECT_FALSE(ids.truth);
	EXPECT_FALSE(scoreAssociations(ids, audit));
	Stats stats;
	setAssociationScoreStats(stats, std::nullopt);
	for (const auto& key : associationScoreKeys())
	{
		ASSERT_TRUE(stats.get(key)) << key;
		EXPECT_FALSE(stats.number(key)) << key;
	}
}

TEST(AssociationScore, AllRejectedStillHasTruth)
{
	// Every measurement rejected: no landmark, but the truth is known, so
	// recall is 0 rather than unknown.
	AssociationAudit audit;
	audit.record({{{K::Rejected, -1}, {K::Rejected, -1}}}, {A, B});
	const auto score = scoreAssociations(landmarkIdentities(audit, {}), audit);
	ASSERT_TRUE(score);
	EXPECT_EQ(score->true_landmarks, 2u);
	EXPECT_FALSE(score->precision);
	EXPECT_DOUBLE_EQ(*score->recall, 0.0);
}

TEST(AssociationAudit, CountsMeasurementsGivenAnIdAndRejected)
{
	StepInput step;
	step.scan = Scan{};
	step.scan->measurements.resize(3);
	step.scan->measurements[0].id = 4;
	step.scan->measurements[2].id = 5;
	AssociationAudit audit;
	EXPECT_FALSE(audit.tracksGivenIds());
	audit.recordGivenIds({{{K::Matched, 4}, {K::New, 9}, {K::Rejected, -1}}}, step);
	EXPECT_TRUE(audit.tracksGivenIds());
	EXPECT_EQ(audit.givenIdCount(), 2u);
	EXPECT_EQ(audit.givenIdRejectedCount(), 1u);
}

}  // namespace
