#pragma once
/// \file VirtualObservation.h
/// A local map as the virtual observation SLSJF fuses (book eq. 5.8):
/// z_map = the local state [end pose; features] with information matrix
/// Lambda. Features the global association leaves out (ambiguous, the
/// authors' "poor observations") are marginalised from it first
/// (marginaliseFeatures, esif/localmap/LocalMapMarginal.h), so what remains
/// keeps exactly the information the map has about the kept part.

#include <esif/localmap/LocalMap.h>

#include <Eigen/Core>
#include <vector>

namespace esif::slsjf
{
struct VirtualObservation
{
	std::vector<std::size_t> kept;	///< indices of the kept features in the local map
	Eigen::VectorXd z;	///< [end pose (3); kept features (2 each)] in the local frame
	Eigen::MatrixXd information;  ///< its information matrix
};

/// The observation of `map` keeping the features flagged in `keep` (one
/// flag per feature). Throws as marginaliseFeatures does.
VirtualObservation keepFeatures(const LocalMap& map, const std::vector<bool>& keep);

}  // namespace esif::slsjf
