#include <esif/association/Ambiguity.h>
#include <esif/association/Chi2.h>
#include <esif/localmap/MapLevelDecisions.h>

#include <stdexcept>

namespace esif
{
MapLevelDecisions decideMapFeatures(const PointSets& sets, const MapLevelAssociationParams& params)
{
	const auto method = params.association == MapAssociationMethod::NearestNeighbor ? AssociationMethod::NearestNeighbor
																				  : AssociationMethod::Jcbb;
	const auto result =
		associatePointSets(sets, method, params.gate_chi2_quantile, params.joint_chi2_quantile, params.search);
	MapLevelDecisions out;
	out.candidate_of = result.candidate_of;
	out.pairs_dropped = result.pairs_dropped;
	out.jcbb_nodes = result.jcbb_nodes;
	out.fell_back = result.fell_back;
	const double new_gate = chi2Quantile(params.new_feature_chi2_quantile, 2);
	const auto& distance2 = params.new_feature_test == NewFeatureTest::GivenPairs ? result.conditional_min_distance2
																				  : result.min_distance2;
	const std::vector<bool> ambiguous =
		ambiguousPairs(sets, result.candidate_of, ambiguityMarginDistance2(params.ambiguity_margin_chi2_quantile));
	for (std::size_t i = 0; i < result.candidate_of.size(); ++i)
	{
		if (ambiguous[i]) out.candidate_of[i] = -1;  // the pair is not taken
		out.outcome.push_back(ambiguous[i]					? MapFeatureOutcome::PoorlyObserved
							  : result.candidate_of[i] >= 0 ? MapFeatureOutcome::Matched
							  : distance2[i] > new_gate	  ? MapFeatureOutcome::New
														  : MapFeatureOutcome::PoorlyObserved);
	}
	return out;
}

MapLevelDecisions decideMapFeaturesGivenAnchors(const PointSets& sets, std::size_t undecided,
												int first_anchor_candidate, const MapLevelAssociationParams& params)
{
	if (undecided > static_cast<std::size_t>(sets.observed.rows()) || first_anchor_candidate < 0 ||
		first_anchor_candidate > sets.candidates.rows() ||
		sets.observed.rows() - static_cast<Eigen::Index>(undecided) != sets.candidates.rows() - first_anchor_candidate)
		throw std::invalid_argument("decideMapFeaturesGivenAnchors: one anchor candidate per anchor point needed");
	MapLevelDecisions out = decideMapFeatures(sets, params);
	out.outcome.resize(undecided);
	out.candidate_of.resize(undecided);
	for (std::size_t u = 0; u < undecided; ++u)
		if (out.candidate_of[u] >= first_anchor_candidate)
		{
			out.candidate_of[u] = -1;
			out.outcome[u] = MapFeatureOutcome::PoorlyObserved;
		}
	return out;
}

MapAssociationTally& MapAssociationTally::operator+=(const MapAssociationTally& o)
{
	seconds += o.seconds;
	candidates += o.candidates;
	pairs_dropped += o.pairs_dropped;
	features_rejected += o.features_rejected;
	jcbb_nodes += o.jcbb_nodes;
	jcbb_fallbacks += o.jcbb_fallbacks;
	id_gate_rejected += o.id_gate_rejected;
	return *this;
}

void MapAssociationTally::appendCounters(std::vector<std::pair<std::string, double>>& counters) const
{
	counters.emplace_back("association_s", seconds);
	counters.emplace_back("association_candidates", static_cast<double>(candidates));
	counters.emplace_back("association_pairs_dropped", static_cast<double>(pairs_dropped));
	counters.emplace_back("features_rejected", static_cast<double>(features_rejected));
	counters.emplace_back("jcbb_nodes", static_cast<double>(jcbb_nodes));
	counters.emplace_back("jcbb_fallbacks", static_cast<double>(jcbb_fallbacks));
	counters.emplace_back("id_gate_rejected", static_cast<double>(id_gate_rejected));
}

void applyMapLevelDecisions(
	const MapLevelDecisions& result, const std::vector<int>& slots, const std::vector<LandmarkId>& candidate_ids,
	StepReport& decisions, MapAssociationTally& tally)
{
	tally.pairs_dropped += result.pairs_dropped;
	tally.jcbb_nodes += result.jcbb_nodes;
	tally.jcbb_fallbacks += result.fell_back ? 1 : 0;
	for (std::size_t u = 0; u < slots.size(); ++u)
	{
		auto& decision = decisions.associations[slots[u]];
		if (result.outcome[u] == MapFeatureOutcome::Matched)
			decision = {Association::Kind::Matched, candidate_ids[result.candidate_of[u]]};
		else if (result.outcome[u] == MapFeatureOutcome::PoorlyObserved)
			decision = {Association::Kind::Rejected, -1};
	}
}

std::size_t rejectedCount(const StepReport& decisions)
{
	std::size_t n = 0;
	for (const auto& a : decisions.associations) n += a.kind == Association::Kind::Rejected;
	return n;
}

}  // namespace esif
