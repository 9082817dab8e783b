#include <esif/association/Chi2.h>
#include <esif/localmap/MapLevelDecisions.h>

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
	for (std::size_t i = 0; i < result.candidate_of.size(); ++i)
		out.outcome.push_back(result.candidate_of[i] >= 0				 ? MapFeatureOutcome::Matched
							  : result.min_distance2[i] > new_gate ? MapFeatureOutcome::New
																	 : MapFeatureOutcome::PoorlyObserved);
	return out;
}

}  // namespace esif
