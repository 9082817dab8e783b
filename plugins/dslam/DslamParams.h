#pragma once
/// \file DslamParams.h
/// Parameters of the D-SLAM plugin, INI section [dslam].

#include <esif/config/ParamBinder.h>
#include <esif/relative/FeatureMap.h>
#include <esif/relative/ReferencePair.h>
#include <esif/relative/RelativeAssociationParams.h>
#include <esif/sparse/SparseRecoveryParams.h>

namespace esif::dslam
{
enum class AdmissiblePolicy
{
	Combine,  ///< Sec. 3.4.1: virtual observations through a small EKF
	Skip	  ///< inadmissible scans do not update the map (loses their information)
};

using relative::MapLinearisation;

/// What covariance intersection fuses (Sec. 3.1.4.4).
enum class FusionScope
{
	/// CI of the robot-pose marginals of the two estimates; the local SLAM's
	/// features then follow their conditional on the robot. Default: with
	/// the joint version, disagreeing feature geometry drags the fused pose
	/// (docs/plugins/dslam.md, "Map frame and fusion").
	Robot,
	/// CI of the whole aligned states [X_r, X_1, ..., X_m1], as in the book.
	Joint
};

struct DslamParams
{
	/// Association mode, gates and candidate margins (Sec. 3.4.2), shared with
	/// D-SLAM map joining. Declared first, so the [dslam] keys keep their order.
	relative::RelativeAssociationParams association;

	relative::ReferencePolicy reference_pair = relative::ReferencePolicy::Widest;  ///< widest | first_mapped
	double reference_min_separation_m = 0.5;  ///< reference features at least this far apart [m]
	double reference_min_angle_deg = 5.0;	  ///< angle f1-robot-f2 within [this, 180 - this] [deg]

	AdmissiblePolicy admissible = AdmissiblePolicy::Combine;  ///< combine | skip
	/// The first this many scans are combined, as in Sec. 3.4.1, into one
	/// observation from the initial pose, which defines the map frame. 1 =
	/// the first scan alone, as the book. More scans pin the frame down
	/// (docs/plugins/dslam.md, "Map frame and fusion").
	int anchor_scans = 20;
	FusionScope fusion = FusionScope::Robot;  ///< robot | joint
	/// The local SLAM holds a feature out of view for this many odometry
	/// steps after its last sighting (LocalSlam.h); 0 = dropped at once, as
	/// the book (docs/plugins/dslam.md, "Holding features out of view").
	int local_hold_steps = 0;
	/// Without IDs, a held mapped feature out of view anchors the map-level
	/// relative tests when the scan has fewer than two tracked anchors and
	/// the local SLAM knows it within this many metres of the robot (larger
	/// of the standard deviations of its predicted range and of its bearing
	/// times the range); 0 = no anchor (docs/plugins/dslam.md,
	/// "Holding features out of view").
	double held_anchor_max_sd_m = 0;

	/// Chi-square confidence of the outlier gates (OutlierGate.h), whatever
	/// the association: a measurement whose innovation exceeds this quantile
	/// against the local SLAM, or whose distances and angles contradict the
	/// map jointly with the scan's others, is rejected (da_rejected). 1 = off.
	/// 0.999: a correct measurement is rejected once in a thousand.
	double outlier_chi2_quantile = 0.999;
	/// Gate on an ID-matched re-observation of a mapped feature the local
	/// SLAM no longer holds (OutlierGate.h: reobservationDistance2), at this
	/// chi-square confidence; the same key and default as the EKF's gate on
	/// known IDs. 1 = off. It assumes a consistent filter, so
	/// configs/vicpark/dslam.ini turns it off (docs/plugins/dslam.md, "The
	/// shipped configs").
	double id_gate_chi2_quantile = 0.9999;
	/// Covariance intersection fuses the map's estimate of the robot pose
	/// (kidnapped robot) with the local SLAM's only when the two agree at
	/// this chi-square confidence (Dslam::robotEstimatesAgree); otherwise
	/// the local estimate stands and the disagreement is counted. 1 = off
	/// (the book fuses always). On, so a wrong match cannot move the robot
	/// through the fusion (docs/plugins/dslam.md, "Outliers and gates").
	double fusion_gate_chi2_quantile = 0.9999;
	/// After this many disagreements in a row, on scans associated by
	/// landmark IDs, the local SLAM is replaced by the map's estimate (robot
	/// and features in view) if that fits the scan: its eq. (3.17) cost is
	/// inside the fusion gate's chi-square quantile (kidnappedFitChi2). 0 =
	/// never (the run then stops as diverged after
	/// divergence_disagreeing_scans). Why: an over-confident local EKF is
	/// otherwise kept by covariance intersection (docs/plugins/dslam.md,
	/// "Linearisation after long dead reckoning").
	int relocalise_after_disagreeing_scans = 5;
	/// A feature is mapped only once a second sighting agrees with its first
	/// at the outlier gate's quantile (esif/association/TentativeFeatures.h); false maps
	/// it at its first sighting, as the book. On, because a mapped feature
	/// cannot be moved or removed (docs/plugins/dslam.md, "Outliers and
	/// gates").
	bool confirm_new_features = true;
	/// ... within this many steps of the first sighting (later, the first
	/// sighting is forgotten and the next one starts again).
	int confirmation_window_steps = 50;
	/// Divergence check (DivergenceGuard.h): a feature estimated farther from
	/// the map origin than this many times (path travelled + largest range
	/// measured) stops the run with a numerical error. 0 = off.
	double divergence_factor = 2.0;
	/// ... and so does a run of this many admissible scans in a row at which
	/// the map's estimate of the robot pose (kidnapped-robot solution)
	/// contradicts the local SLAM's (DivergenceGuard.h). 0 = off.
	int divergence_disagreeing_scans = 20;
	/// Every this many steps (and at the end), the map updates are evaluated
	/// again at the current estimate (FeatureMap::relinearise). 0 = never, as
	/// the book's EIF, whose old updates then hold a region a loop closure
	/// turned at its old orientation (docs/plugins/dslam.md, "Relinearising
	/// the map updates").
	int relinearise_every_steps = 200;
	/// ... only the updates whose features' relative geometry (offsets from
	/// the update's f1) moved more than this since they were evaluated [m];
	/// 0 = all. 1 cm is a tenth of the range noise.
	double relinearise_threshold_m = 0.01;
	/// After a map update that changes the relative geometry of the scan's
	/// features by more than this (a loop closure: metres), the map updates
	/// are relinearised at once, up to `relinearise_iterations` passes
	/// (Gauss-Newton on the static map). 0 = only every
	/// relinearise_every_steps. On, so the robot is not localised on a map
	/// linearised metres off (docs/plugins/dslam.md, "Linearisation after
	/// long dead reckoning").
	double relinearise_on_correction_m = 0.2;
	int relinearise_iterations = 5;
	MapLinearisation map_linearisation = MapLinearisation::Shared;
	/// Gauss-Newton iterations of the kidnapped-robot solution (eq.
	/// 3.17-3.18, KidnappedRobot.h); 1 = the book's single linearised step.
	/// More, because at loop closure eq. (3.18) may start the robot far off
	/// (docs/plugins/dslam.md, "Linearisation after long dead reckoning").
	int kidnapped_iterations = 10;

	SparseRecoveryParams recovery;	///< recovery, reordering, n0, ... (Sec. 3.3)

	void declare(ParamBinder& b);
	relative::ReferenceRules referenceRules() const;
};

}  // namespace esif::dslam
