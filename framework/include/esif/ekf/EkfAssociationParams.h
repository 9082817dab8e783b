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
	SearchBounds search;  ///< when JCBB falls back to nearest neighbour

	/// The chi-square value of id_gate_chi2_quantile (+inf when disabled).
	double idGateDistance2() const;

	void declare(ParamBinder& b);
};

}  // namespace esif
