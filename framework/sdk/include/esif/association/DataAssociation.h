#pragma once
/// \file DataAssociation.h
/// Range-bearing data association, Mahalanobis metric and chi-square gate:
/// nearest neighbour through MRPT's mrpt::slam::data_association_full_
/// covariance, JCBB (Neira & Tardos 2001) by the framework's own search
/// (src/association/Jcbb.h says why: MRPT 2.5's bound returns the first
/// maximal hypothesis, not the closest), with what MRPT leaves to the
/// caller: bearing wrap-around (it subtracts angles plainly) and telling a
/// new feature from an ambiguous measurement. JCBB runs only while the
/// problem is within SearchBounds; beyond them, nearest neighbour with the
/// joint compatibility test (SearchBounds.h explains why and how).

#include <esif/association/SearchBounds.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace esif
{
enum class AssociationMethod
{
	NearestNeighbor,
	Jcbb
};

struct AssociationInput
{
	Eigen::MatrixXd observations;  ///< M x 2: (range [m], bearing [rad])
	Eigen::MatrixXd predictions;  ///< N x 2: predicted (range, bearing) of candidate landmarks
	Eigen::MatrixXd covariance;	 ///< 2N x 2N: joint innovation covariance H P H^T + R
};

struct AssociationResult
{
	/// For each observation, the index of its candidate, or -1 when none passed the gate.
	std::vector<int> candidate_of;
	/// For each observation, the smallest squared Mahalanobis distance to any
	/// candidate (infinity when there are none): tells "new" from "ambiguous".
	std::vector<double> min_distance2;
	std::size_t jcbb_nodes = 0;
	/// Ambiguity measured before the search (SearchBounds.h).
	SearchEffort effort;
	/// JCBB was asked for but the problem exceeded the bounds: nearest
	/// neighbour with the joint compatibility test was used instead.
	bool fell_back = false;
	/// Pairs the joint compatibility test of the fallback removed.
	std::size_t pairs_dropped = 0;
};

/// Squared Mahalanobis distance of every (observation, prediction) pair
/// (M x N), bearings compared across the wrap, with the prediction's
/// diagonal block of `covariance` (infinity where it is not positive
/// definite): the individual compatibility that associate() gates on.
Eigen::MatrixXd individualDistances2(const AssociationInput& input);

/// Associates observations to candidates; `gate_quantile` in (0, 1) is the
/// individual-compatibility chi-square confidence (2 dof), also that of the
/// fallback's joint test (2 dof per pair).
AssociationResult associate(
	const AssociationInput& input, AssociationMethod method, double gate_quantile, const SearchBounds& bounds = {});

}  // namespace esif
