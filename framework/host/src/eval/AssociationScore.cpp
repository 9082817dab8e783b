/// \file AssociationScore.cpp
/// Landmarks found, duplicated and spurious, association precision and
/// recall; see AssociationScore.h.

#include <esif/eval/AssociationScore.h>
#include <esif/eval/LandmarkIdentities.h>

namespace esif
{
namespace
{
std::optional<double> shareOf(std::size_t part, std::size_t whole)
{
	if (whole == 0) return std::nullopt;
	return static_cast<double>(part) / static_cast<double>(whole);
}
}  // namespace

std::optional<AssociationScore> scoreAssociations(const LandmarkIdentities& identities, const AssociationAudit& audit)
{
	if (!audit.hasTruth()) return std::nullopt;
	AssociationScore s;
	s.true_landmarks = audit.trueLandmarks().size();
	s.used = audit.newCount() + audit.matchedCount();
	s.with_truth = audit.measurementsWithTruth();
	const auto primary = primaryLandmarks(identities);
	s.found = primary.size();
	std::size_t identified = 0;
	for (const LandmarkIdentity& row : identities.landmarks)
	{
		if (!row.true_id)
		{
			++s.spurious;
			continue;
		}
		++identified;
		// Only the landmark that stands for the true one holds correct associations.
		if (primary.at(*row.true_id) == row.landmark) s.correct += row.votes;
	}
	s.duplicated = identified - s.found;
	s.precision = shareOf(s.correct, s.used);
	s.recall = shareOf(s.correct, s.with_truth);
	return s;
}

const std::vector<std::string>& associationScoreKeys()
{
	static const std::vector<std::string> keys = {"landmarks_true",		"landmarks_found", "landmarks_duplicated",
												  "landmarks_spurious", "da_precision",	   "da_recall"};
	return keys;
}

void setAssociationScoreStats(Stats& stats, const std::optional<AssociationScore>& score)
{
	const auto& k = associationScoreKeys();
	if (!score)
	{
		for (const auto& key : k) stats.set(key, StatValue(nullptr));
		return;
	}
	const auto count = [](std::size_t n) { return StatValue(static_cast<long long>(n)); };
	stats.set(k[0], count(score->true_landmarks));
	stats.set(k[1], count(score->found));
	stats.set(k[2], count(score->duplicated));
	stats.set(k[3], count(score->spurious));
	stats.set(k[4], score->precision);
	stats.set(k[5], score->recall);
}

}  // namespace esif
