#pragma once
/// \file StaircaseUpdate.h
/// A low-rank update I += C C^T recombined for cholmod_updown.

#include <Eigen/Core>

namespace esif
{
/// The columns of one update C, its rows sorted by position, recombined as
/// C Q (Q orthogonal: the same C C^T) into a lower staircase: column j
/// starts at the j-th touched position. cholmod_updown takes C eight
/// columns at a time and walks, for each group, the elimination-tree paths
/// from its columns' first rows to the root. As whitened (eq. 3.15, 5.9) a
/// dense measurement information makes nearly every column hold the
/// deepest variable of the update, so every group walks the longest path;
/// in staircase form only the first group does, the later ones start ever
/// higher, and an update with more columns than rows loses the excess. The
/// staircase is R^T from the QR factorisation of C^T (C C^T = R^T R).
Eigen::MatrixXd staircase(const Eigen::MatrixXd& C);

}  // namespace esif
