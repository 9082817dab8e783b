#pragma once
/// \file StateNees.h
/// The book authors' consistency test of a whole estimate: the normalised
/// estimation error squared of the full state (every feature and, where the
/// state holds them, every pose) against the truth or a reference,
///     NEES = e^T I e,    e = x - x_ref,
/// with the back-end's full information matrix I, compared with the
/// two-sided 95% interval of the chi-square distribution of dim(e) degrees
/// of freedom (Sec. 5.6.1 of the book judges SLSJF consistent this way).
/// Unlike the per-landmark 95% ellipses it sees the correlations: a map
/// whose features are each inside their ellipse but share one over-confident
/// rotation fails it.
///
/// Variables without a reference (a landmark the truth does not know, a pose
/// of no step) are marginalised out, not dropped: the NEES of the rest is
/// e_s^T (I_ss - I_su I_uu^-1 I_us) e_s, with I_uu factored by CHOLMOD, so
/// no large matrix is ever inverted.

#include <esif/core/StateInformation.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>

namespace esif
{
/// The reference the state is compared with (ground truth, or another run),
/// in the frame of the initial robot pose.
struct StateReference
{
	std::map<LandmarkId, Eigen::Vector2d> landmarks;  ///< by the reference's IDs
	std::map<std::size_t, Pose2> poses_by_step;	 ///< the pose after rawlog step k
	std::map<std::size_t, Pose2> poses_by_local_map;  ///< the end pose of local map k
};

struct StateNees
{
	double nees = 0;
	std::size_t dof = 0;  ///< scalars compared: 2 per landmark, 3 per pose
	std::size_t landmarks_compared = 0;
	std::size_t poses_compared = 0;
	std::size_t variables_marginalised = 0;	 ///< without a reference
	double lower95 = 0;	 ///< chi-square(dof) 2.5% quantile
	double upper95 = 0;	 ///< chi-square(dof) 97.5% quantile
	bool consistent() const { return nees >= lower95 && nees <= upper95; }
};

/// The truth as a reference: its landmarks, and path row k as the pose after
/// rawlog step k.
StateReference stateReferenceOf(const GroundTruth& truth);

/// Another run's outputs as a reference (e.g. the full-SLAM optimum): its
/// landmarks by their true landmarks when its landmark_identities.txt has
/// them (the landmark that stands for each, LandmarkIdentities.h), else by
/// ID; trajectory row k as the pose after step k when it has exactly
/// `steps` rows (else no poses: the rows cannot be paired).
StateReference stateReferenceOf(const RunOutputs& run, std::size_t steps);

/// NEES of `state` against `reference`. A landmark is compared with the
/// reference landmark `to_reference` maps its ID to (the identity when
/// `to_reference` is nullopt; unmapped ones are marginalised); a pose with
/// the reference pose of its step, else of its local map. Headings are
/// compared wrapped to (-pi, pi]. Returns nullopt when nothing can be
/// compared. Throws NumericalError naming `what` when the information of the
/// marginalised variables is not positive definite, or the result is not
/// finite.
std::optional<StateNees> stateNees(
	const StateInformation& state, const StateReference& reference,
	const std::optional<std::map<LandmarkId, LandmarkId>>& to_reference, const std::string& what);

}  // namespace esif
