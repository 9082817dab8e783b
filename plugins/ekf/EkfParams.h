#pragma once
/// \file EkfParams.h
/// Parameters of the EKF SLAM plugin, INI section [ekf].

#include <esif/association/DataAssociation.h>
#include <esif/config/ParamBinder.h>

namespace esif
{
enum class EkfAssociation
{
	Auto,  ///< known_ids when the measurement carries an ID, otherwise jcbb
	KnownIds,
	NearestNeighbor,
	Jcbb
};

struct EkfParams
{
	EkfAssociation association = EkfAssociation::Auto;	///< auto | known_ids | nn | jcbb
	double gate_chi2_quantile = 0.99;  ///< individual-compatibility gate confidence, in (0, 1)
	/// An unassociated measurement starts a new landmark only if its smallest
	/// squared Mahalanobis distance to every candidate exceeds this chi-square
	/// quantile; otherwise it is ambiguous and rejected (no duplicate landmarks).
	double new_landmark_chi2_quantile = 0.9999;
	double candidate_margin_m = 2.0;  ///< candidates: predicted range <= max range + this [m]
	double candidate_margin_deg = 10.0;	 ///< ... and bearing within half the field of view + this [deg]

	void declare(ParamBinder& b);
};

}  // namespace esif
