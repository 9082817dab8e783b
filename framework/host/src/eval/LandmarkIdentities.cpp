/// \file LandmarkIdentities.cpp
/// A final map's landmarks identified with true landmarks; see LandmarkIdentities.h.

#include <esif/eval/LandmarkIdentities.h>

namespace esif
{
LandmarkIdentities landmarkIdentities(const AssociationAudit& audit, const std::vector<LandmarkEstimate>& map)
{
	LandmarkIdentities out;
	out.truth = audit.hasTruth();
	const auto to_true = audit.filterToTrue();
	for (const LandmarkEstimate& lm : map)
	{
		LandmarkIdentity row;
		row.landmark = lm.id;
		row.measurements = audit.usedOn(lm.id);
		if (const auto it = to_true.find(lm.id); it != to_true.end())
		{
			row.true_id = it->second;
			row.votes = audit.votesFor(lm.id, it->second);
		}
		out.landmarks.push_back(row);
	}
	return out;
}

std::map<LandmarkId, LandmarkId> primaryLandmarks(const LandmarkIdentities& identities)
{
	std::map<LandmarkId, const LandmarkIdentity*> best;
	for (const LandmarkIdentity& row : identities.landmarks)
	{
		if (!row.true_id) continue;
		const LandmarkIdentity*& holder = best[*row.true_id];
		if (!holder || row.votes > holder->votes || (row.votes == holder->votes && row.landmark < holder->landmark))
			holder = &row;
	}
	std::map<LandmarkId, LandmarkId> out;
	for (const auto& [true_id, row] : best) out.emplace(true_id, row->landmark);
	return out;
}

}  // namespace esif
