#pragma once
/// \file RelativeAssociationParams.h
/// How D-SLAM associates measurements with mapped features (book Sec.
/// 3.4.2): landmark IDs, or MRPT nearest-neighbour / JCBB hypotheses
/// verified on relative distances and angles (eq. 3.45), and the gates.
/// In the framework with RelativeAssociation, which serves D-SLAM (Ch. 3)
/// and D-SLAM map joining (Ch. 4). Declared inside the section of whoever
/// runs the association ([dslam] for the D-SLAM plugin), with the same keys
/// everywhere.

#include <esif/association/SearchBounds.h>
#include <esif/config/ParamBinder.h>

namespace esif::relative
{
/// The association rule. RelativeAssociation itself forms NN or JCBB
/// hypotheses; Auto and KnownIds are decided by the caller, which holds the
/// IDs.
enum class AssociationMode
{
	Auto,			  ///< known_ids when every measurement carries an ID, else jcbb
	KnownIds,		  ///< the rawlog's landmark IDs
	NearestNeighbor,  ///< MRPT nearest neighbour hypotheses, verified by eq. (3.45)
	Jcbb			  ///< MRPT JCBB hypotheses, verified by eq. (3.45)
};

struct RelativeAssociationParams
{
	AssociationMode association = AssociationMode::Auto;  ///< auto | known_ids | nn | jcbb
	/// Individual-compatibility gate of the hypotheses, from the pose
	/// estimate with robot-map correlations taken as zero (Sec. 3.4.2).
	double gate_chi2_quantile = 0.99;
	/// Confidence alpha of the joint test on relative distances and angles,
	/// eq. (3.45).
	double relative_gate_chi2_quantile = 0.99;
	/// An unmatched measurement starts a new feature only beyond this
	/// chi-square quantile from every candidate; otherwise it is rejected.
	double new_landmark_chi2_quantile = 0.9999;
	/// A match the relative test could not check (the only one of its
	/// scan, no tracked feature beside it) rests on the absolute gate alone,
	/// from a robot estimate D-SLAM does not correlate with the map: it is
	/// dropped (the measurement waits) while another candidate the sensor
	/// could tell apart is within this chi-square quantile (2 dof) of it
	/// (association/Ambiguity.h). A wrong feature fused into the map's EIF
	/// stays there; a measurement left out costs one sighting. 0 = off.
	double ambiguity_margin_chi2_quantile = 0.99;
	double candidate_margin_m = 2.0;	 ///< candidates: predicted range <= max range + this [m]
	double candidate_margin_deg = 10.0;	 ///< ... and bearing within half the field of view + this [deg]
	/// ... both widened by this many standard deviations of the predicted
	/// range and bearing from the robot's uncertainty. After a long stretch
	/// of dead reckoning a fixed margin left a mapped feature in view out of
	/// the candidates, and its next sighting was mapped a second time.
	double candidate_margin_sigmas = 3.0;
	/// When the JCBB hypotheses give way to nearest neighbour with the joint
	/// test (keys jcbb_max_candidates, jcbb_max_hypotheses).
	SearchBounds search;

	void declare(ParamBinder& b);
};

}  // namespace esif::relative
