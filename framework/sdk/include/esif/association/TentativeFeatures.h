#pragma once
/// \file TentativeFeatures.h
/// Tentative landmarks: a landmark enters a map only when a second sighting
/// confirms the first (a two-of-N track initiation, as in target
/// tracking), and an unconfirmed sighting is dropped, never fused. The book
/// maps a feature at its first sighting; a single bad return then plants a
/// feature that no later measurement can move: with a misread landmark ID
/// the feature sits at its neighbour's place and the gates reject every
/// correct sighting after it; with clutter, the spurious feature becomes a
/// reference for later scans; without IDs, a measurement of a mapped
/// landmark that missed its gate starts a duplicate. An information-form
/// map cannot remove a feature once its measurements are fused, so the
/// check has to come before. Used by D-SLAM and by the EKF with
/// association by distance (LandmarkEkf: the EKF plugin and every local-map
/// builder).
///
/// A first sighting is held as a tentative feature: its position in the map
/// frame from the local SLAM's robot, with covariance J_r P_r J_r^T +
/// J_z R J_z^T. A later sighting confirms it when the two positions agree at
/// the gate's chi-square(2) quantile, taking the two as independent (the
/// robot's error common to both only shrinks the true difference, so the
/// test is conservative). With landmark IDs the sighting is compared with
/// the tentative feature of the same ID, and a disagreeing sighting replaces
/// it; without IDs, with the nearest tentative feature inside the gate.
/// Tentative features expire after `window_steps`.

#include <esif/core/StepInput.h>

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

namespace esif
{
class TentativeFeatures
{
   public:
	TentativeFeatures(double gate_chi2, std::size_t window_steps)
		: gate_chi2_(gate_chi2), window_steps_(window_steps)
	{
	}

	/// A sighting of a feature not in the map, at `position` (covariance
	/// `cov`) in the map frame, at step `step`; `id` is its landmark ID when
	/// the data carries one. True when it confirms an earlier sighting: the
	/// tentative feature is then consumed and the caller maps the feature.
	/// False: the sighting is now held as tentative.
	bool confirm(std::optional<LandmarkId> id, const Eigen::Vector2d& position, const Eigen::Matrix2d& cov,
				 std::size_t step);

	std::size_t tentativeCount() const { return tentative_.size(); }
	/// Drops the tentative features older than the window at `step`.
	void expire(std::size_t step);

   private:
	struct Tentative
	{
		std::optional<LandmarkId> id;
		Eigen::Vector2d position;
		Eigen::Matrix2d cov;
		std::size_t step = 0;
	};

	/// Index of the tentative feature this sighting is compared with.
	std::optional<std::size_t> partner(std::optional<LandmarkId> id, const Eigen::Vector2d& position,
									   const Eigen::Matrix2d& cov) const;
	double distance2(const Tentative& t, const Eigen::Vector2d& position, const Eigen::Matrix2d& cov) const;

	double gate_chi2_;
	std::size_t window_steps_;
	std::vector<Tentative> tentative_;
};

}  // namespace esif
