#pragma once
/// \file MapAssociation.h
/// Data association of a local map with the global map (book Sec. 5.4.1):
/// select the earlier local maps that can overlap the new one (their radii,
/// the start poses' uncertainty and a margin, Sec. 5.4.1.1) and of their
/// features those near one of the new map's (by the estimates, within the
/// start pose's position and heading uncertainty plus the margin), recover the
/// joint covariance of their features and of the new map's start pose only
/// (eq. 3.25), move those features into the new map's frame with the full
/// first-order covariance (which includes the start-pose/candidate
/// correlation that eq. 5.13 leaves out), and associate them with the local
/// features (PointSetAssociation: JCBB or MRPT NN, exact joint test). An
/// unmatched local feature is new when it is far from every candidate, and
/// left out as ambiguous otherwise (the authors' "poor observation").

#include "GlobalMap.h"
#include "SlsjfParams.h"

#include <esif/localmap/LocalMap.h>
#include <esif/localmap/MapLevelDecisions.h>

#include <Eigen/Core>
#include <optional>

namespace esif::slsjf
{
struct MapAssociationOutcome
{
	/// One per local feature: Matched (global id), New (proposed id = the
	/// local id) or Rejected.
	StepReport decisions;
	MapExtent extent;  ///< for the overlap tests of later maps
	std::size_t maps_selected = 0;
	/// What the search found (candidates, pairs dropped, JCBB nodes and
	/// fallbacks, ID-gate rejections); the fusion adds time and rejections.
	MapAssociationTally tally;
};

/// Extent of a local map: the farthest of its end position and features
/// from its origin, each plus `sigmas` standard deviations (square root of
/// the largest eigenvalue of its 2x2 covariance block).
double mapRadius(const LocalMap& map, const Eigen::MatrixXd& local_cov, double sigmas);

/// Equal IDs are one feature: Matched when the global map has the ID, else
/// New; but a local feature whose global feature of the same ID, moved into
/// the local map's frame with the start pose, fails the chi-square gate
/// params.id_gate_chi2_quantile (2 dof, covariance of both sides) is
/// Rejected: left out of the fusion (marginalised from the local map). Not
/// New: an ID names one feature, and the local feature carries a misread
/// ID (its position belongs to another feature), so as a new feature it
/// would be a spurious one. The gate is checked per feature, not jointly,
/// for the reason LandmarkEkf gives.
MapAssociationOutcome associateByIds(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, std::optional<VarId> start, GlobalMap& global,
	const SlsjfParams& params);

/// For a map whose features carry global IDs from its scans' association
/// (local_map_global_features_radius_m), after associateByIds: the features
/// whose ID the global map does not hold (the scans found no global feature
/// for them, or it was out of reach) are associated as
/// associateGeometrically associates every feature, against the global
/// features no feature of the map is matched to, and given the matched ones:
/// they join the joint test as anchors (decideMapFeaturesGivenAnchors). A
/// map whose start pose is uncertain after a blind drive otherwise matched
/// its other features by a turn its matched ones rule out (MRCLAM robot 5;
/// docs/plugins/slsjf.md has the trace and the measurements). A scan
/// decides on one sighting, the map level on the feature all its sightings
/// placed, so a feature the scans could not place near a global one gets a
/// second look before it starts a global feature (docs/plugins/slsjf.md,
/// "Association with the global map").
void associateUnidentifiedGeometrically(const LocalMap& map, const Eigen::MatrixXd& local_cov, VarId start,
										GlobalMap& global, const SlsjfParams& params, MapAssociationOutcome& outcome);

/// Sec. 5.4.1 as above. `local_cov` is the local state's covariance,
/// `start` the map's start pose variable (from GlobalMap::startPose).
MapAssociationOutcome associateGeometrically(
	const LocalMap& map, const Eigen::MatrixXd& local_cov, std::optional<VarId> start, GlobalMap& global,
	const SlsjfParams& params);

}  // namespace esif::slsjf
