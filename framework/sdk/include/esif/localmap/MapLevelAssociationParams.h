#pragma once
/// \file MapLevelAssociationParams.h
/// How a map-joining filter associates the features of a closed local map
/// with its global map, and the gates it applies: the keys SLSJF ([slsjf],
/// Sec. 5.4.1) and D-SLAM map joining ([dslam_lmj], Sec. 4.4.2) share. Where
/// the candidates come from and in which frame they are compared is the
/// plugin's own; the plugin's parameter struct derives from this one.

#include <esif/association/SearchBounds.h>
#include <esif/config/ParamBinder.h>

namespace esif
{
enum class MapAssociationMethod
{
	Auto,  ///< known_ids when the local features' IDs identify them, else jcbb
	KnownIds,  ///< equal IDs are one feature (the authors' AssumeDataAssoc = 1)
	Jcbb,  ///< JCBB with the exact joint covariance (esif::associatePointSets)
	NearestNeighbor	 ///< MRPT nearest neighbour on the same candidates
};

/// Against what an unmatched local feature's distance to the candidates is
/// judged new (MapLevelDecisions.h).
enum class NewFeatureTest
{
	Alone,	   ///< each candidate on its own (the authors')
	GivenPairs	///< conditioned on the map's accepted pairs
};

struct MapLevelAssociationParams
{
	MapAssociationMethod association = MapAssociationMethod::Auto;	///< auto | known_ids | jcbb | nn
	double gate_chi2_quantile = 0.99;  ///< individual compatibility of a local/global pair, 2 dof
	double joint_chi2_quantile = 0.99;	///< exact joint compatibility of a map's pairs, 2 dof per pair
	/// An unmatched local feature starts a global feature only beyond this
	/// quantile from every candidate; otherwise it is ambiguous and left out
	/// of the update (the authors' "poor observation").
	double new_feature_chi2_quantile = 0.9999;
	/// ... from every candidate alone, or given the map's accepted pairs
	/// (PointAssociation::conditional_min_distance2): with the placement
	/// error the pairs share taken out, a sighting beside a mapped feature is
	/// new rather than left out, but a local map more confident than it
	/// should be then starts duplicates (docs/plugins/dslam_lmj.md, "New or
	/// poorly observed").
	NewFeatureTest new_feature_test = NewFeatureTest::Alone;
	/// A matched local feature that another candidate, standing apart from
	/// its own, explains nearly as well given the map's other pairs (within
	/// this chi-square quantile, 2 dof: ambiguousPairs) is left out; 0 = off.
	double ambiguity_margin_chi2_quantile = 0;
	/// With IDs: a local feature whose same-ID global feature fails this
	/// chi-square quantile (2 dof) is left out (misread ID); 1 = no gate.
	/// 0.9999 as the local-map builder's gate (LandmarkEkf).
	double id_gate_chi2_quantile = 0.9999;
	SearchBounds search;  ///< when JCBB falls back to nearest neighbour (jcbb_max_*)

	/// The chi-square value of id_gate_chi2_quantile (+inf when disabled).
	double idGateDistance2() const;

	/// Declares the keys above; `association_doc` says where the plugin's
	/// candidates come from.
	void declareAssociation(ParamBinder& b, const char* association_doc);
};

}  // namespace esif
