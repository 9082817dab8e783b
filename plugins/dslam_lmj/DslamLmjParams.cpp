#include "DslamLmjParams.h"

namespace esif::lmj
{
void DslamLmjParams::declare(ParamBinder& b)
{
	declareAssociation(b, "upper-level association of local features: equal IDs, or JCBB / MRPT NN in the frame of two "
						  "common features known from the local level (Sec. 4.4.2); auto = IDs when the input has them, "
						  "else jcbb");
	b.real("region_margin_m", region_margin_m, "margin of the region pruning around the reference feature [m]",
		   Bounds::nonNegative());
	b.real("region_sigmas", region_sigmas, "sigmas of the reference feature's global uncertainty in the region",
		   Bounds::nonNegative());
	b.enumeration<UpperLevelFrame>(
		"upper_level_frame", upper_level_frame,
		{{"pair", UpperLevelFrame::Pair}, {"start_pose", UpperLevelFrame::StartPose}},
		"without IDs, local features meet the global candidates in the frame of two features known from the local "
		"level (pair, the book) or in the map's frame placed by its start pose (start_pose: the previous map's end "
		"pose, Sec. 4.4.1; no known feature needed; region: region_sigmas of the placement's uncertainty plus "
		"region_margin_m)");
	b.real("reference_min_separation_m", reference_min_separation_m,
		   "reference features f1, f2 of a local map at least this far apart [m]", Bounds::positive());
	b.real("reference_min_clearance_m", reference_min_clearance_m,
		   "no other feature of the map within this of f1 or f2 [m]", Bounds::nonNegative());
	b.real("reference_pair_chi2_quantile", reference_pair_chi2_quantile,
		   "a robot pose placed by a pair of global features must agree with its map's start composed with its pose "
		   "in that map within this chi-square quantile (3 dof): the open map's robot between fusions, and a map's "
		   "end pose before its fusion (a failing pair's matches are left out); 1 = off",
		   Bounds{0, 1, true, false});
	relative::declareMapLinearisation(b, map_linearisation);
	b.flag("relinearise_after_fusion", relinearise_after_fusion,
		   "after each fusion, evaluate every map update again at the current estimate (Gauss-Newton over the "
		   "global map); false = never (the book)");
	b.integer("relinearise_iterations", relinearise_iterations,
			  "passes of each such relinearisation (each stops early when no update moved)", Bounds::atLeast(1));
	b.real("relinearise_threshold_m", relinearise_threshold_m,
		   "relinearise only the map updates whose features' relative geometry moved more than this since their "
		   "last linearisation [m]",
		   Bounds::nonNegative());
	builder.declare(b);
	recovery.declare(b);
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
