#pragma once
/// \file Jcbb.h
/// Joint Compatibility Branch and Bound (Neira & Tardos, IEEE T-RA 2001):
/// the hypothesis that pairs the most observations with candidates, all of
/// them jointly compatible, and among those the one of smallest joint
/// Mahalanobis distance.
///
/// Written here rather than taken from mrpt::slam::data_association_full_
/// covariance (MRPT 2.5), whose bound leaves out the pairing of the
/// observation being branched on: once a hypothesis with k pairs is found,
/// any other that can only tie is pruned, so the search returns the first
/// maximal hypothesis in index order, not the closest. With one observation
/// and two compatible landmarks it took the one at d^2 = 6.3 over the one at
/// 0.9 (MRCLAM robot 4, step 10), which turned the robot by 0.7 rad. MRPT's
/// also takes no covariance of the observations: the points of a local map
/// matched against the global map (PointSetAssociation.cpp) share their
/// map's errors, and without those correlations a rotated but rigid local
/// map fails a joint test it passes (MRCLAM robot 4, a local map of two
/// features after a blind drive: both pairs at d^2 = 4.1 of 4 dof, where
/// MRPT's kept one wrong pair). Problem::Sz carries them.

#include <esif/association/Chi2.h>

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace esif::jcbb
{
struct Problem
{
	const Eigen::MatrixXd& z;  ///< M x 2 observations (bearings on the same side of the cut as y's)
	const Eigen::MatrixXd& y;  ///< N x 2 predictions
	const Eigen::MatrixXd& S;  ///< 2N x 2N joint innovation covariance
	const Eigen::MatrixXd& d2;	///< M x N individual squared distances
	double quantile;  ///< chi-square confidence of the individual and the joint tests
	/// 2M x 2M covariance of the observations themselves, when they are
	/// estimates with errors of their own (a local map's features); pair
	/// (i, c) and (j, d) then covary by Sz(i, j) + S(c, d). nullptr: none
	/// (measurement noise already in S).
	const Eigen::MatrixXd* Sz = nullptr;
};

struct Hypothesis
{
	std::vector<int> candidate_of;	///< per observation, its candidate or -1
	std::size_t nodes = 0;	///< search nodes explored
};

/// The best hypothesis of `problem` (see the file comment).
Hypothesis search(const Problem& problem);

/// The pairs (i, candidate_of[i] >= 0) stacked: their innovations, joint
/// covariance, and the observation and candidate of each pair.
struct JointInnovation
{
	Eigen::VectorXd nu;
	Eigen::MatrixXd S;
	std::vector<Eigen::Index> observations, candidates;
};
/// `Sz`: as Problem::Sz.
JointInnovation jointInnovation(const Eigen::MatrixXd& z, const Eigen::MatrixXd& y, const Eigen::MatrixXd& S,
								const std::vector<int>& candidate_of, const Eigen::MatrixXd* Sz = nullptr);

/// Exact joint squared Mahalanobis distance of the pairs (i, candidate_of[i] >= 0).
double jointDistance2(const Eigen::MatrixXd& z, const Eigen::MatrixXd& y, const Eigen::MatrixXd& S,
					  const std::vector<int>& candidate_of, const Eigen::MatrixXd* Sz = nullptr);

/// The joint test of pairs stacked in `nu` (two rows each, joint
/// covariance `S`) against `bound`, and when it fails the pair to drop: the
/// one that contributes most to nu^T S^-1 nu. Removing pair a lowers it by
/// x_a^T [(S^-1)_aa]^-1 x_a with x = S^-1 nu, so the test's factorisation
/// serves every pair. (The pair farthest on its own is not it: a wrong pair
/// can be the nearest individually, and dropping by individual distance
/// then removes every right pair first.)
struct JointVerdict
{
	double distance2 = 0;  ///< nu^T S^-1 nu; infinity when S is not positive definite
	bool passes = true;	 ///< distance2 <= bound
	Eigen::Index blamed = -1;  ///< when it fails: the pair to drop; -1 when S is not positive definite
};
JointVerdict jointVerdict(const Eigen::VectorXd& nu, const Eigen::MatrixXd& S, double bound);

/// The joint-compatibility repair both associations share: while the pairs
/// of `candidate_of`, stacked by `stack` (anything with nu, S and the
/// observations of its pairs), fail the joint test at `quantile` (2 dof per
/// pair), the pair jointVerdict blames is dropped; `fallback` (given the
/// stack) names the observation to drop when the joint covariance is not
/// positive definite. Returns the pairs dropped; `distance2` is the last
/// joint distance (0 without pairs).
template <class Stack, class Fallback>
std::size_t dropUntilJointlyCompatible(std::vector<int>& candidate_of, double quantile, Stack stack,
									   Fallback fallback, double& distance2)
{
	std::size_t dropped = 0;
	for (;;)
	{
		const auto joint = stack(candidate_of);
		const auto pairs = static_cast<int>(joint.observations.size());
		distance2 = 0;
		if (pairs == 0) return dropped;
		const JointVerdict verdict = jointVerdict(joint.nu, joint.S, chi2Quantile(quantile, 2 * pairs));
		distance2 = verdict.distance2;
		if (verdict.passes) return dropped;
		candidate_of[verdict.blamed >= 0 ? joint.observations[verdict.blamed] : fallback(joint)] = -1;
		++dropped;
	}
}

}  // namespace esif::jcbb
