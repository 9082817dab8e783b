#include <esif/association/Chi2.h>
#include <esif/localmap/MapLevelAssociationParams.h>

namespace esif
{
void MapLevelAssociationParams::declareAssociation(ParamBinder& b, const char* association_doc)
{
	b.enumeration<MapAssociationMethod>("association", association,
										{{"auto", MapAssociationMethod::Auto},
										 {"known_ids", MapAssociationMethod::KnownIds},
										 {"jcbb", MapAssociationMethod::Jcbb},
										 {"nn", MapAssociationMethod::NearestNeighbor}},
										association_doc);
	b.real("gate_chi2_quantile", gate_chi2_quantile, "individual-compatibility gate of a local/global pair",
		   Bounds::openUnit());
	b.real("joint_chi2_quantile", joint_chi2_quantile, "joint-compatibility gate of all pairs of a map",
		   Bounds::openUnit());
	b.real("new_feature_chi2_quantile", new_feature_chi2_quantile,
		   "confidence beyond which an unmatched local feature is new, not ambiguous (then left out)",
		   Bounds::openUnit());
	b.enumeration<NewFeatureTest>("new_feature_test", new_feature_test,
								  {{"alone", NewFeatureTest::Alone}, {"given_pairs", NewFeatureTest::GivenPairs}},
								  "an unmatched local feature's distance to each candidate: alone (the authors'), or "
								  "given the map's accepted pairs (their shared placement error taken out)");
	b.real("ambiguity_margin_chi2_quantile", ambiguity_margin_chi2_quantile,
		   "a matched local feature is left out when, given the map's other pairs, a candidate standing apart from "
		   "its own is within this chi-square quantile (2 dof) of being as likely; 0 = off",
		   Bounds{0, 1, false, true});
	b.real("id_gate_chi2_quantile", id_gate_chi2_quantile,
		   "with IDs, a local feature whose same-ID global feature fails this chi-square quantile is left out "
		   "(misread ID); 1 = no gate",
		   Bounds{0, 1, true, false});
	search.declare(b);
}

double MapLevelAssociationParams::idGateDistance2() const
{
	return chi2GateBound(id_gate_chi2_quantile, 2);
}

}  // namespace esif
