#pragma once
/// \file PreviousMapMatcher.h
/// Which features of the open local map are features of the previous map,
/// when measurements carry no landmark IDs (book Sec. 4.4.4: "this can be
/// easily checked by the data association in the local map"). The previous
/// map's features are moved into the open map's frame (its start pose is the
/// previous end pose, or that pose composed with the link odometry) with
/// their full first-order covariance, and associated with the open map's
/// features by PointSetAssociation (the two maps are independent).

#include <esif/association/DataAssociation.h>
#include <esif/localmap/LocalMap.h>

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace esif
{
/// The open map's features to match: positions in its own frame and their
/// joint covariance (2M x 2M).
struct OpenMapFeatures
{
	Eigen::MatrixXd positions;	///< M x 2
	Eigen::MatrixXd covariance;	 ///< 2M x 2M
};

/// For each open-map feature, the index in `previous.features` of the
/// feature it is, or nullopt. `previous` must carry its covariance (maps the
/// builder made do); `link` is the odometry from the previous end pose to
/// the open map's start pose, if the maps do not share it.
std::vector<std::optional<std::size_t>> matchPreviousMap(
	const LocalMap& previous, const std::optional<OdometryIncrement>& link, const OpenMapFeatures& open,
	AssociationMethod method, double gate_quantile);

}  // namespace esif
