#pragma once
/// \file EkfAssociationParams.h
/// Which measurements of a scan an EKF SLAM filter uses and how it
/// associates them with its landmarks: landmark IDs, MRPT nearest neighbour or MRPT JCBB, and the
/// gates. Declared inside the section of whoever runs the filter ([ekf] for
/// the EKF plugin, a joining plugin's section for its local-map builder), with
/// the same keys everywhere.

#include <esif/association/SearchBounds.h>
#include <esif/config/ParamBinder.h>

namespace esif
{
enum class EkfAssociation
{
	Auto,  ///< known_ids when every measurement of the scan carries an ID, otherwise jcbb
	KnownIds,
	NearestNeighbor,
	Jcbb
};

struct EkfAssociationParams
{
	EkfAssociation association = EkfAssociation::Auto;	///< auto | known_ids | nn | jcbb
	double gate_chi2_quantile = 0.99;  ///< individual-compatibility gate confidence, in (0, 1)
	/// An unassociated measurement starts a new landmark only if its smallest
	/// squared Mahalanobis distance to every candidate exceeds this chi-square
	/// quantile; otherwise it is ambiguous and rejected (no duplicate landmarks).
	double new_landmark_chi2_quantile = 0.9999;
	/// Tentative landmarks (association/TentativeFeatures.h): a measurement
	/// associated by distance that would start a landmark is held until a
	/// second sighting within confirmation_window_steps agrees with it (at
	/// the new-landmark gate); until then it is Rejected, neither mapped
	/// nor fused. A landmark seen once never enters the map.
	bool confirm_new_landmarks = false;
	int confirmation_window_steps = 50;
	/// A scan's lone match (JCBB had no second pair to decide with) waits
	/// (Rejected, neither fused nor a new landmark) while another candidate
	/// the sensor could tell apart is nearly as likely:
	/// within this chi-square quantile (2 dof) of squared Mahalanobis
	/// distance (association/Ambiguity.h). 0 = off (nearest neighbour or
	/// JCBB decide alone).
	double ambiguity_margin_chi2_quantile = 0;
	double candidate_margin_m = 2.0;  ///< candidates: predicted range <= max range + this [m]
	double candidate_margin_deg = 10.0;	 ///< ... and bearing within half the field of view + this [deg]
	/// Measurements of features closer than this are not used [m]. The
	/// bearing of a feature within a few robot-position sigmas is far from
	/// linear in the pose (its Jacobian grows as 1/range), so one EKF update
	/// with it can turn the heading; a local map built with such updates is
	/// inconsistent, and the error stays frozen in it. 0 = use every one.
	double min_range_m = 0;
	/// Outlier gate of measurements associated by their landmark ID: one
	/// whose innovation against the prior fails this chi-square quantile
	/// (2 dof) is not fused (a misread ID moves the robot by the distance
	/// between the two landmarks). 0.9999 (18.4) rejects 1 in 10^4 correct
	/// measurements of a consistent filter, while a wrong ID on a map whose
	/// landmarks are metres apart gives distances of hundreds. 1 disables it.
	double id_gate_chi2_quantile = 0.9999;
	/// Iterated EKF update (IteratedUpdate in EkfSlamCore.h): an update
	/// whose linearisation error exceeds relinearise_above_d2 (squared
	/// sigmas of the sensor noise) is relinearised at its own estimate, at
	/// most update_iterations linearisations in all; 1 = the plain EKF of
	/// eq. (1.9)-(1.10). After a long stretch of dead reckoning the first
	/// re-observation of a mapped landmark can have an innovation of metres:
	/// linearised at the prior only, the update overshoots and P shrinks as
	/// if it had not (long_gap.ini: a 3.5 m correction at 5 m range left
	/// the pose NEES at 77), and the ID gate then rejects every later
	/// sighting of the loop. Below 1 sigma^2 the linear model is as good
	/// as the measurement; on long_gap.ini 2 of ~1550 updates exceed it
	/// (errors of 104 and 7.7 sigma^2, the loop closure and the re-entry
	/// after the last crossing; the next largest is 0.28).
	int update_iterations = 10;
	double relinearise_above_d2 = 1.0;
	/// Without IDs: two landmarks, each matched by distance at least this
	/// many times, whose estimates have become one point within the
	/// chi-square quantile merge_chi2_quantile (2 dof) are merged into one
	/// (ekf/CoincidentLandmarks.h). 0 = never. Declared by declareMerging()
	/// only: a map-joining filter's local maps do not merge, since their
	/// global map would not know the merged landmarks as one.
	int merge_landmarks_after_matches = 0;
	double merge_chi2_quantile = 0.99;
	SearchBounds search;  ///< when JCBB falls back to nearest neighbour

	/// The chi-square value of id_gate_chi2_quantile (+inf when disabled).
	double idGateDistance2() const;
	/// The chi-square value of ambiguity_margin_chi2_quantile (0 when off).
	double ambiguityMarginDistance2() const;

	/// Every key but the merging ones.
	void declare(ParamBinder& b);
	/// merge_landmarks_after_matches and merge_chi2_quantile.
	void declareMerging(ParamBinder& b);
};

}  // namespace esif
