#include <esif/relative/RelativeAssociationParams.h>

namespace esif::relative
{
void RelativeAssociationParams::declare(ParamBinder& b)
{
	b.enumeration<AssociationMode>(
		"association", association,
		{{"auto", AssociationMode::Auto},
		 {"known_ids", AssociationMode::KnownIds},
		 {"nn", AssociationMode::NearestNeighbor},
		 {"jcbb", AssociationMode::Jcbb}},
		"data association: the rawlog's landmark IDs, or MRPT nearest-neighbour / JCBB hypotheses verified on "
		"relative distances and angles (eq. 3.45); auto = IDs when present, else jcbb");
	b.real("gate_chi2_quantile", gate_chi2_quantile, "individual-compatibility gate of the hypotheses",
		   Bounds::openUnit());
	b.real("relative_gate_chi2_quantile", relative_gate_chi2_quantile,
		   "confidence of the joint test on relative distances and angles, eq. (3.45)", Bounds::openUnit());
	b.real("new_landmark_chi2_quantile", new_landmark_chi2_quantile,
		   "confidence beyond which an unmatched measurement is a new feature, not an ambiguous one",
		   Bounds::openUnit());
	b.real("ambiguity_margin_chi2_quantile", ambiguity_margin_chi2_quantile,
		   "a match the relative test could not check (alone in its scan) is dropped while another candidate "
		   "the sensor could tell apart is within this chi-square quantile (2 dof) of it; 0 = off",
		   Bounds{0, 1, false, true});
	b.real("candidate_margin_m", candidate_margin_m, "range margin for association candidates [m]",
		   Bounds::nonNegative());
	b.real("candidate_margin_deg", candidate_margin_deg, "bearing margin for association candidates [deg]",
		   Bounds::closed(0, 180));
	b.real("candidate_margin_sigmas", candidate_margin_sigmas,
		   "candidate margins widened by this many standard deviations of the predicted range and bearing "
		   "(robot uncertainty)",
		   Bounds::nonNegative());
	search.declare(b);
}

}  // namespace esif::relative
