#include "DslamParams.h"

#include <cmath>

namespace esif::dslam
{
void DslamParams::declare(ParamBinder& b)
{
	association.declare(b);
	b.enumeration<relative::ReferencePolicy>(
		"reference_pair", reference_pair,
		{{"widest", relative::ReferencePolicy::Widest}, {"first_mapped", relative::ReferencePolicy::FirstMapped}},
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
	b.integer("local_hold_steps", local_hold_steps,
			  "the local SLAM holds a feature out of view for this many odometry steps after its last sighting; "
			  "0 = dropped at once (the book)",
			  Bounds::nonNegative());
	b.real("held_anchor_max_sd_m", held_anchor_max_sd_m,
		   "without IDs, held mapped features known within this many metres of the robot anchor the relative tests "
		   "of scans with fewer than two tracked anchors; 0 = none",
		   Bounds::nonNegative());
	b.real("outlier_chi2_quantile", outlier_chi2_quantile,
		   "chi-square confidence of the localisation and mapping outlier gates (any association); 1 = off",
		   Bounds{0, 1, true, false});
	b.real("id_gate_chi2_quantile", id_gate_chi2_quantile,
		   "chi-square confidence of the gate on re-observations of mapped features out of the local SLAM's view; "
		   "1 = off",
		   Bounds{0, 1, true, false});
	b.real("fusion_gate_chi2_quantile", fusion_gate_chi2_quantile,
		   "fuse the map's and the local SLAM's robot estimates only when they agree at this chi-square "
		   "confidence; 1 = off (the book)",
		   Bounds{0, 1, true, false});
	b.integer("relocalise_after_disagreeing_scans", relocalise_after_disagreeing_scans,
			  "after this many disagreements in a row on scans associated by IDs, replace the local SLAM by the "
			  "map's estimate when that fits the scan at the fusion gate's quantile; 0 = never",
			  Bounds::nonNegative());
	b.flag("confirm_new_features", confirm_new_features,
		   "map a feature only when a second sighting agrees with its first at the outlier gate; false = map it "
		   "at its first sighting (the book)");
	b.integer("confirmation_window_steps", confirmation_window_steps,
			  "a first sighting waits this many steps for the sighting that confirms it", Bounds::atLeast(1));
	b.real("divergence_factor", divergence_factor,
		   "stop with a numerical error when a feature lies farther from the origin than this times (path + "
		   "range); 0 = off",
		   Bounds::nonNegative());
	b.integer("divergence_disagreeing_scans", divergence_disagreeing_scans,
			  "stop with a numerical error when the map and the local SLAM disagree on the robot pose at this many "
			  "admissible scans in a row; 0 = off",
			  Bounds::nonNegative());
	b.integer("relinearise_every_steps", relinearise_every_steps,
			  "every N steps, relinearise every map update at the current estimate; 0 = never (the book)",
			  Bounds::nonNegative());
	b.real("relinearise_threshold_m", relinearise_threshold_m,
		   "relinearise only the map updates whose features' relative geometry moved more than this since their "
		   "last evaluation [m]; 0 = all",
		   Bounds::nonNegative());
	b.real("relinearise_on_correction_m", relinearise_on_correction_m,
		   "relinearise at once after a map update that changes the relative geometry of the scan's features by "
		   "more than this [m]; 0 = off",
		   Bounds::nonNegative());
	b.integer("relinearise_iterations", relinearise_iterations,
			  "passes of the relinearisation after such a correction (each stops early when no update moved)",
			  Bounds::atLeast(1));
	relative::declareMapLinearisation(b, map_linearisation);
	b.integer("kidnapped_iterations", kidnapped_iterations,
			  "Gauss-Newton iterations of the kidnapped-robot solution, eq. (3.17)-(3.18); 1 = the book's single step",
			  Bounds::atLeast(1));
	recovery.declare(b);
}

relative::ReferenceRules DslamParams::referenceRules() const
{
	return {reference_pair, reference_min_separation_m, reference_min_angle_deg * M_PI / 180.0};
}

}  // namespace esif::dslam
