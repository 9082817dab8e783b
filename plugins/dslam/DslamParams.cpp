#include "DslamParams.h"

#include <cmath>

namespace esif::dslam
{
void DslamParams::declare(ParamBinder& b)
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
	b.real("candidate_margin_m", candidate_margin_m, "range margin for association candidates [m]",
		   Bounds::nonNegative());
	b.real("candidate_margin_deg", candidate_margin_deg, "bearing margin for association candidates [deg]",
		   Bounds::closed(0, 180));
	b.enumeration<ReferencePolicy>(
		"reference_pair", reference_pair,
		{{"widest", ReferencePolicy::Widest}, {"first_mapped", ReferencePolicy::FirstMapped}},
		"reference features f1, f2: the longest well-conditioned baseline, or the two mapped earliest");
	b.real("reference_min_separation_m", reference_min_separation_m,
		   "reference features closer than this are not a pair [m]", Bounds::nonNegative());
	b.real("reference_min_angle_deg", reference_min_angle_deg,
		   "the angle f1-robot-f2 must lie in [this, 180 - this] [deg]", Bounds::closed(0, 89));
	b.enumeration<AdmissiblePolicy>(
		"admissible", admissible, {{"combine", AdmissiblePolicy::Combine}, {"skip", AdmissiblePolicy::Skip}},
		"scans seeing fewer than two mapped features: combine into virtual observations (Sec. 3.4.1) or skip");
	b.integer("anchor_scans", anchor_scans,
			  "the first N scans, combined from the exactly known initial pose, anchor the map frame",
			  Bounds::atLeast(1));
	b.enumeration<FusionScope>("fusion", fusion, {{"robot", FusionScope::Robot}, {"joint", FusionScope::Joint}},
							   "covariance intersection of the robot-pose marginals (robot) or of the whole aligned "
							   "states of the local SLAM and the kidnapped-robot solution (joint, the book's)");
	recovery.declare(b);
}

ReferenceRules DslamParams::referenceRules() const
{
	return {reference_pair, reference_min_separation_m, reference_min_angle_deg * M_PI / 180.0};
}

}  // namespace esif::dslam
