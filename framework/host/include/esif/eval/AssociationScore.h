#pragma once
/// \file AssociationScore.h
/// How well a run mapped and associated, scored against the true landmark
/// of each measurement (LandmarkIdentities.h), with no ground-truth
/// positions needed:
/// - true landmarks: distinct true landmarks among the measurements (used
///   or rejected);
/// - found: true landmarks some landmark of the final map is identified with;
/// - duplicated: landmarks identified with a true landmark another landmark
///   already stands for;
/// - spurious: landmarks with no identity (none of their measurements came
///   from a landmark: simulated clutter; or they have no measurement);
/// - a measurement is correctly associated when the filter used it on the
///   landmark that stands for its true landmark; precision = correct / used
///   (new or matched), recall = correct / measurements with a true landmark.
/// A landmark split in two therefore costs precision and recall for the
/// measurements its duplicate took, as it should: they were not associated
/// with the landmark they belong to. A filter that re-creates a landmark at
/// every sighting has precision and recall near 0, however exact each copy.

#include <esif/eval/AssociationAudit.h>
#include <esif/formats/LandmarkIdentityFile.h>
#include <esif/formats/StatsJson.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
struct AssociationScore
{
	std::size_t true_landmarks = 0;
	std::size_t found = 0;
	std::size_t duplicated = 0;
	std::size_t spurious = 0;
	std::size_t used = 0;  ///< measurements used (new or matched)
	std::size_t correct = 0;  ///< used on the landmark that stands for their true landmark
	std::size_t with_truth = 0;	 ///< measurements with a true landmark (used or rejected)
	std::optional<double> precision;  ///< correct / used; none when nothing was used
	std::optional<double> recall;  ///< correct / with_truth
};

/// The score of a final map (`identities`, LandmarkIdentities.h) and of the
/// measurements of `audit`; nullopt when no measurement carried its true
/// landmark.
std::optional<AssociationScore> scoreAssociations(const LandmarkIdentities& identities, const AssociationAudit& audit);

/// The stats keys of the score, in table order: landmarks_true,
/// landmarks_found, landmarks_duplicated, landmarks_spurious, da_precision,
/// da_recall.
const std::vector<std::string>& associationScoreKeys();

/// Sets associationScoreKeys() (every one null without a score).
void setAssociationScoreStats(Stats& stats, const std::optional<AssociationScore>& score);

}  // namespace esif
