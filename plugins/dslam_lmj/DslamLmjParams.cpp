#include "DslamLmjParams.h"

#include <esif/association/Chi2.h>


namespace esif::lmj
{
void DslamLmjParams::declare(ParamBinder& b)
{
	b.enumeration<UpperAssociation>(
		"association", association,
		{{"auto", UpperAssociation::Auto},
		 {"known_ids", UpperAssociation::KnownIds},
		 {"jcbb", UpperAssociation::Jcbb},
		 {"nn", UpperAssociation::NearestNeighbor}},
		"upper-level association of local features: equal IDs, or MRPT JCBB / NN in the frame of two common "
		"features known from the local level (Sec. 4.4.2); auto = IDs when the input has them, else jcbb");
	b.real("gate_chi2_quantile", gate_chi2_quantile, "individual-compatibility gate of a local/global pair",
		   Bounds::openUnit());
	b.real("joint_chi2_quantile", joint_chi2_quantile, "joint-compatibility gate of all pairs of a map",
		   Bounds::openUnit());
	b.real("new_feature_chi2_quantile", new_feature_chi2_quantile,
		   "confidence beyond which an unmatched local feature is new, not ambiguous (then left out)",
		   Bounds::openUnit());
	b.real("region_margin_m", region_margin_m, "margin of the region pruning around the reference feature [m]",
		   Bounds::nonNegative());
	b.real("region_sigmas", region_sigmas, "sigmas of the reference feature's global uncertainty in the region",
		   Bounds::nonNegative());
	b.real("reference_min_separation_m", reference_min_separation_m,
		   "reference features f1, f2 of a local map at least this far apart [m]", Bounds::positive());
	b.real("reference_min_clearance_m", reference_min_clearance_m,
		   "no other feature of the map within this of f1 or f2 [m]", Bounds::nonNegative());
	b.real("id_gate_chi2_quantile", id_gate_chi2_quantile,
		   "with IDs, an ID-matched local feature that fails this chi-square quantile against its global feature "
		   "(in a reference pair's frame) is left out (misread ID); 1 = no gate",
		   Bounds{0, 1, true, false});
	b.integer("relinearise_iterations", relinearise_iterations,
			  "Gauss-Newton passes over the global map after each fusion (every map update evaluated again at the "
			  "current estimate); 0 = never (the book)",
			  Bounds::nonNegative());
	b.real("relinearise_threshold_m", relinearise_threshold_m,
		   "relinearise only the map updates whose features' relative geometry moved more than this since their "
		   "last linearisation [m]",
		   Bounds::nonNegative());
	search.declare(b);
	builder.declare(b);
	recovery.declare(b);
}

double DslamLmjParams::idGateDistance2() const
{
	return chi2GateBound(id_gate_chi2_quantile, 2);
}

LocalMapBuilderParams DslamLmjParams::defaultBuilder()
{
	LocalMapBuilderParams p;
	p.local_map_min_common_features = 2;
	return p;
}

SparseRecoveryParams DslamLmjParams::defaultRecovery()
{
	SparseRecoveryParams r;
	r.reordering = Reordering::Camd;
	r.n0 = 1000;
	return r;
}

}  // namespace esif::lmj
