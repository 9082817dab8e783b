#pragma once
/// \file LocalMapMarginal.h
/// A local map with some of its features marginalised out: what both
/// map-joining filters do with a feature they cannot use. SLSJF fuses a map
/// without the features its global association leaves out (the authors'
/// poor observations, book Sec. 5.4.1); D-SLAM map joining joins a map with
/// its neighbour without a feature the two place apart (Sec. 4.4.4). In
/// either case what remains must keep exactly the information the map has
/// about the kept part, no more (the dropped feature's own sightings are
/// not fused twice) and no less.

#include <esif/localmap/LocalMap.h>

#include <vector>

namespace esif
{
/// `map` with only the features flagged in `keep` (one flag per feature, in
/// the map's order; the end pose is always kept). Its information is the
/// Schur complement Lambda_aa - Lambda_ab Lambda_bb^-1 Lambda_ba of the
/// dropped block b, symmetrised; its covariance, when the map has one, the
/// kept block; with nothing dropped, the map as it is. Every other field
/// (step reports included) is the map's: a caller that reports the dropped
/// features' sightings otherwise edits them. Throws std::invalid_argument
/// when `keep` or a matrix does not match the map's size, and
/// NumericalError naming the map when the dropped block is not positive
/// definite.
LocalMap marginaliseFeatures(const LocalMap& map, const std::vector<bool>& keep);

}  // namespace esif
