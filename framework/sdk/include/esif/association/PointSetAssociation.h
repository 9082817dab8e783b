#pragma once
/// \file PointSetAssociation.h
/// Association of two sets of 2-D points with full Gaussian uncertainty, in
/// one Cartesian frame: the features of a local map against features of an
/// earlier map or of the global map moved into the local map's frame (book
/// Sec. 4.4.2 and 5.4.1). The two sets are independent (a local map is built
/// from its own data), so the innovation of a pair (i, c) is z_i - y_c with
/// covariance Pz_ii + Py_cc, and of a joint hypothesis the sum of the two
/// joint blocks.
///
/// JCBB (Neira & Tardos 2001) is esif's own (Jcbb.h), every joint test with
/// the exact joint covariance, the observed points' own included: the
/// points of one local map share its errors (its robot's heading after a
/// blind drive turns them all), which MRPT's data_association_full_covariance
/// cannot take (one covariance per prediction, none per observation), and
/// without which a rigid but rotated map fails a joint test it passes.
/// Nearest neighbour is MRPT's (Mahalanobis metric), each prediction given
/// its covariance plus that of its nearest observation (exact for the
/// individual test of the natural pair); its pairs are then exchanged while
/// that lowers the summed exact individual distances at the same number of
/// pairs. Either hypothesis is finally checked with the exact joint
/// covariance; while it fails, the pair the joint test blames most is
/// dropped.
///
/// JCBB runs only while the problem is within SearchBounds (counted on the
/// exact individual distances); beyond them nearest neighbour gives the
/// hypothesis, which the same exchange and joint test then refine.

#include <esif/association/DataAssociation.h>

#include <Eigen/Core>
#include <vector>

namespace esif
{
struct PointSets
{
	Eigen::MatrixXd observed;  ///< M x 2: points to associate (e.g. local-map features)
	Eigen::MatrixXd observed_cov;  ///< 2M x 2M: their joint covariance
	Eigen::MatrixXd candidates;	 ///< N x 2: candidate points in the same frame
	Eigen::MatrixXd candidates_cov;	 ///< 2N x 2N: their joint covariance
};

struct PointAssociation
{
	/// For each observed point, the index of its candidate, or -1.
	std::vector<int> candidate_of;
	/// For each observed point, the smallest exact squared Mahalanobis
	/// distance to any candidate (infinity when there is none): tells a new
	/// point from an ambiguous one.
	std::vector<double> min_distance2;
	/// For each observed point left unpaired, the smallest squared distance
	/// to any candidate given the accepted pairs: the rise of the joint
	/// distance were that pair added, with the pairs' correlated innovations
	/// (a shared placement error) taken out. The same as min_distance2 when
	/// no pair is accepted; infinity for paired points.
	std::vector<double> conditional_min_distance2;
	/// Exact joint squared Mahalanobis distance of the accepted pairs.
	double joint_distance2 = 0;
	/// Pairs MRPT proposed that the exact joint test removed.
	std::size_t pairs_dropped = 0;
	std::size_t jcbb_nodes = 0;
	/// Ambiguity measured before the search (SearchBounds.h).
	SearchEffort effort;
	/// JCBB was asked for but exceeded the bounds: nearest neighbour instead.
	bool fell_back = false;
};

/// Associates `sets.observed` with `sets.candidates`. `gate_quantile` is the
/// individual-compatibility confidence (2 dof), `joint_quantile` that of the
/// exact joint test (2 dof per pair); both in (0, 1). Throws
/// std::invalid_argument on inconsistent sizes.
PointAssociation associatePointSets(const PointSets& sets, AssociationMethod method, double gate_quantile,
									double joint_quantile, const SearchBounds& bounds = {});

/// For each observed point paired in `candidate_of` (a result of
/// associatePointSets): whether, given the other pairs (their shared
/// placement error taken out), another candidate j explains the point
/// nearly as well, within `margin_d2` (ambiguityMarginDistance2), while
/// standing apart from the chosen one by at least margin_d2 in the pair's
/// own conditional covariance: the map-level form of Ambiguity.h. Twins
/// closer than that cost alike whichever is picked; candidates farther
/// apart move the map by their distance when the wrong one is taken, and a
/// local map whose features are poorly placed (after a blind drive) can
/// pass the joint test with the wrong one. All false when margin_d2 <= 0.
std::vector<bool> ambiguousPairs(const PointSets& sets, const std::vector<int>& candidate_of, double margin_d2);

}  // namespace esif
