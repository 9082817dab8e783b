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
	/// features then follow their conditional on the robot. Default: on
	/// grid196 the joint version below let a disagreement of the two
	/// estimates' relative feature geometry (each confident to millimetres
	/// in some direction) drag the fused pose 1.7 m away from both.
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
	/// the first scan alone, as the book: the frame is then known only to
	/// about sigma_range / baseline of that scan's features (0.7 deg, 0.34 m
	/// rigid error on grid196); 20 scans bring it to the EKF's level.
	int anchor_scans = 20;
	FusionScope fusion = FusionScope::Robot;  ///< robot | joint

	/// Chi-square confidence of the outlier gates (OutlierGate.h), whatever
	/// the association: a measurement whose innovation exceeds this quantile
	/// against the local SLAM, or whose distances and angles contradict the
	/// map jointly with the scan's others, is rejected (da_rejected). 1 = off.
	/// 0.999: a correct measurement is rejected once in a thousand.
	double outlier_chi2_quantile = 0.999;
	/// Gate on an ID-matched re-observation of a mapped feature the local
	/// SLAM no longer holds (OutlierGate.h: reobservationDistance2), at this
	/// chi-square confidence; the same key and default as the EKF's gate on
	/// known IDs. 1 = off. Like every gate on known IDs it assumes a
	/// consistent filter: on Victoria Park, where the robot's heading
	/// estimate is not, it rejected 2,785 valid loop-closing sightings, so
	/// configs/vicpark/dslam.ini turns it off.
	double id_gate_chi2_quantile = 0.9999;
	/// Covariance intersection fuses the map's estimate of the robot pose
	/// (kidnapped robot) with the local SLAM's only when the two agree at
	/// this chi-square confidence (Dslam::robotEstimatesAgree); otherwise
	/// the local estimate stands and the disagreement is counted. 1 = off
	/// (the book fuses always). On configs/sim/long_gap.ini without IDs, a
	/// wrong match after the gap moved the robot 30 m through the fusion.
	/// Off in configs/vicpark/dslam.ini for the reason given above.
	double fusion_gate_chi2_quantile = 0.9999;
	/// After this many disagreements in a row, on scans associated by
	/// landmark IDs, the local SLAM is replaced by the map's estimate (robot
	/// and features in view) if that fits the scan: its eq. (3.17) cost is inside the fusion gate's chi-square
	/// quantile (kidnappedFitChi2). The local SLAM is an EKF; like any, it
	/// grows over-confident in its heading over a long run, and once it
	/// is, covariance intersection keeps it (it minimises the fused
	/// covariance) and the gate refuses the map's estimate: on long_gap,
	/// the robot came back to the start 12 m off, claiming 2.3 m, with the
	/// map right. 0 = never (the run then stops as diverged after
	/// divergence_disagreeing_scans).
	int relocalise_after_disagreeing_scans = 5;
	/// A feature is mapped only once a second sighting agrees with its first
	/// at the outlier gate's quantile (esif/association/TentativeFeatures.h); false maps
	/// it at its first sighting, as the book. On configs/sim/wrong_ids.ini
	/// (1% misread IDs) the first sighting of 24 features was a misread; each
	/// then sat at its neighbour's place for good.
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
	/// the book's EIF: then an update keeps the Jacobian of the map as it was
	/// when it came, and once a loop closure turns a region of the map, its
	/// old updates hold it at its old orientation with information that
	/// relative measurements do not have (their Jacobian's null space no
	/// longer contains the rotation of the current map). On grid1225 that
	/// left the whole map turned 2.5 deg about the start with 0.3% of the
	/// features inside their 95% ellipse; relinearising every 200 steps: 1.0
	/// deg (the full-SLAM optimum's 0.8 deg), 95.6%, for a replay 2-3 times
	/// as long (docs/plugins/dslam.md, "Relinearising the map updates").
	int relinearise_every_steps = 200;
	/// ... only the updates whose features' relative geometry (offsets from
	/// the update's f1) moved more than this since they were evaluated [m];
	/// 0 = all. 1 cm is a tenth of the range noise.
	double relinearise_threshold_m = 0.01;
	/// After a map update that changes the relative geometry of the scan's
	/// features by more than this (a loop closure: metres), the map updates
	/// are relinearised at once, up to `relinearise_iterations` passes
	/// (Gauss-Newton on the static map). 0 = only every
	/// relinearise_every_steps. The update that closes long_gap's loop,
	/// linearised where the features were 3.5 m off, left 76 features
	/// outside their 99.9% ellipse until the next periodic pass, and the
	/// robot was localised on that map in between.
	double relinearise_on_correction_m = 0.2;
	int relinearise_iterations = 5;
	MapLinearisation map_linearisation = MapLinearisation::Shared;
	/// Gauss-Newton iterations of the kidnapped-robot solution (eq.
	/// 3.17-3.18, KidnappedRobot.h); 1 = the book's single linearised step.
	/// At loop closure the reference pair may pair an old, precise feature
	/// with one mapped after a gap, metres off: eq. (3.18) then starts the
	/// robot tens of degrees off, and one step from there put long_gap's
	/// robot 8 m off with 0.2 m standard deviation.
	int kidnapped_iterations = 10;

	SparseRecoveryParams recovery;	///< recovery, reordering, n0, ... (Sec. 3.3)

	void declare(ParamBinder& b);
	relative::ReferenceRules referenceRules() const;
};

}  // namespace esif::dslam
