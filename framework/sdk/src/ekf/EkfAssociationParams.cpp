#include <esif/association/Ambiguity.h>
#include <esif/association/Chi2.h>
#include <esif/ekf/EkfAssociationParams.h>


namespace esif
{
void EkfAssociationParams::declare(ParamBinder& b)
{
	b.enumeration<EkfAssociation>(
		"association", association,
		{{"auto", EkfAssociation::Auto},
		 {"known_ids", EkfAssociation::KnownIds},
		 {"nn", EkfAssociation::NearestNeighbor},
		 {"jcbb", EkfAssociation::Jcbb}},
		"data association: landmark IDs from the rawlog, MRPT nearest neighbour or MRPT JCBB; auto = IDs when "
		"present, else JCBB");
	b.real("gate_chi2_quantile", gate_chi2_quantile, "individual-compatibility chi-square gate confidence",
		   Bounds::openUnit());
	b.real("new_landmark_chi2_quantile", new_landmark_chi2_quantile,
		   "confidence beyond which an unmatched measurement is a new landmark, not an ambiguous one",
		   Bounds::openUnit());
	b.flag("confirm_new_landmarks", confirm_new_landmarks,
		   "without IDs, a new landmark enters the map only when a second sighting within "
		   "confirmation_window_steps agrees with the first (tentative landmarks); unconfirmed sightings are "
		   "neither mapped nor fused");
	b.integer("confirmation_window_steps", confirmation_window_steps,
			  "steps a tentative landmark waits for its confirming sighting", Bounds::atLeast(1));
	b.real("ambiguity_margin_chi2_quantile", ambiguity_margin_chi2_quantile,
		   "a match is taken only when every other candidate's squared Mahalanobis distance exceeds the chosen "
		   "one's by this chi-square quantile (2 dof); else the measurement waits (rejected); 0 = off",
		   Bounds{0, 1, false, true});
	b.real("candidate_margin_m", candidate_margin_m, "range margin for association candidates [m]",
		   Bounds::nonNegative());
	b.real("candidate_margin_deg", candidate_margin_deg, "bearing margin for association candidates [deg]",
		   Bounds::closed(0, 180));
	b.real("min_range_m", min_range_m,
		   "measurements of features closer than this are not used (their bearing is not linearisable) [m]",
		   Bounds::nonNegative());
	b.real("id_gate_chi2_quantile", id_gate_chi2_quantile,
		   "a measurement associated by its landmark ID whose innovation fails this chi-square quantile is "
		   "rejected (misread ID); 1 = no gate",
		   Bounds{0, 1, true, false});
	b.integer("update_iterations", update_iterations,
			  "at most this many linearisations of the measurement model per update (iterated EKF, "
			  "Gauss-Newton); 1 = plain EKF",
			  Bounds::atLeast(1));
	b.real("relinearise_above_d2", relinearise_above_d2,
		   "an update is iterated when its linear model misses the measurement model at the corrected state by "
		   "more than this squared Mahalanobis distance (sensor noise)",
		   Bounds::nonNegative());
	search.declare(b);
}

void EkfAssociationParams::declareMerging(ParamBinder& b)
{
	b.integer("merge_landmarks_after_matches", merge_landmarks_after_matches,
			  "without IDs, two landmarks each matched at least this many times whose estimates have become one "
			  "point (merge_chi2_quantile) are merged into one; 0 = never",
			  Bounds::atLeast(0));
	b.real("merge_chi2_quantile", merge_chi2_quantile,
		   "two landmarks are one point when the squared Mahalanobis distance of their difference is within this "
		   "chi-square quantile (2 dof)",
		   Bounds::openUnit());
}

double EkfAssociationParams::ambiguityMarginDistance2() const
{
	return esif::ambiguityMarginDistance2(ambiguity_margin_chi2_quantile);
}

double EkfAssociationParams::idGateDistance2() const
{
	return chi2GateBound(id_gate_chi2_quantile, 2);
}

}  // namespace esif
