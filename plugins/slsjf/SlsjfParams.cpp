#include "SlsjfParams.h"

namespace esif::slsjf
{
void SlsjfParams::declare(ParamBinder& b)
{
	declareAssociation(b, "global association of local features: equal IDs, or JCBB / MRPT NN on the overlapping maps' "
						  "features (Sec. 5.4.1); auto = IDs when the input has them, else jcbb");
	b.real("overlap_margin_m", overlap_margin_m, "slack of the overlap test between local maps [m]",
		   Bounds::nonNegative());
	b.real("overlap_sigmas", overlap_sigmas, "sigmas added to map radii and start-pose uncertainty in the overlap test",
		   Bounds::nonNegative());
	b.enumeration<FusionJacobians>(
		"jacobians", jacobians,
		{{"current", FusionJacobians::Current},
		 {"first_estimates", FusionJacobians::FirstEstimates},
		 {"observability_constrained", FusionJacobians::ObservabilityConstrained}},
		"where each fusion (eq. 5.9) is linearised: current = at the current estimate (the book's SLSJF); "
		"first_estimates = at each variable's first estimate, the innovation still at the current one (FEJ); "
		"observability_constrained = at the current estimate, projected onto the rigid-motion null space of the "
		"first estimates");
	b.enumeration<Smoothing>(
		"smoothing", smoothing,
		{{"none", Smoothing::None}, {"final", Smoothing::Final}, {"every_k_maps", Smoothing::EveryKMaps}},
		"relinearise every fused map at the current estimate (iterated SLSJF): never, after the last map, or "
		"every smoothing_every_maps maps");
	b.integer("smoothing_every_maps", smoothing_every_maps, "K of smoothing = every_k_maps", Bounds::atLeast(1));
	b.integer("smoothing_max_iterations", smoothing_max_iterations, "Gauss-Newton iterations per relinearisation",
			  Bounds::atLeast(1));
	b.real("smoothing_tolerance", smoothing_tolerance,
		   "relinearisation stops when no estimate moves more than this [m or rad]", Bounds::positive());
	builder.declare(b);
	recovery.declare(b);
}

SparseRecoveryParams SlsjfParams::defaultRecovery()
{
	SparseRecoveryParams r;
	r.reordering = Reordering::NestedDissection;
	r.reorder_trigger = ReorderTrigger::FillGrowth;
	r.max_fill_growth = 0.2;
	r.n0 = 1000;  // the trailing part's bound if reorder_trigger = trailing_dimension
	return r;
}

}  // namespace esif::slsjf
