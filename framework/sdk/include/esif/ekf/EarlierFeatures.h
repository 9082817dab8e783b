#pragma once
/// \file EarlierFeatures.h
/// Features a map-joining filter's global map already holds, moved into the
/// frame of the local map being built, with their joint covariance. The
/// local-map builder associates each scan with them as well as with the
/// map's own features (LocalMapBuilder::setEarlierFeatures): a sighting
/// matched to one starts a local feature under that feature's global ID, so
/// the map level checks the match (book Sec. 5.4.1, by ID) instead of
/// guessing it from the whole map after the fact.
///
/// They are not part of the local map's state: the local map stays
/// independent of the global map (its information enters the global map
/// once, eq. 5.8). Their covariance is independent of the local map's
/// state for the same reason: the local map starts at its origin with zero
/// covariance.

#include <esif/core/Pose2.h>
#include <esif/core/StepInput.h>

#include <Eigen/Core>
#include <vector>

namespace esif
{
struct EarlierFeatures
{
	std::vector<LandmarkId> ids;  ///< global IDs, one per feature
	Eigen::VectorXd positions;	///< 2n: (x, y) of each feature in the local map's frame
	Eigen::MatrixXd covariance;	 ///< 2n x 2n: their joint covariance in that frame

	std::size_t size() const { return ids.size(); }
	Eigen::Vector2d position(std::size_t i) const { return positions.segment<2>(2 * static_cast<Eigen::Index>(i)); }
	/// The features seen from a frame at `frame` of this one, whose pose is
	/// known with covariance `frame_cov` independently of them (a link
	/// odometry, eq. 5.4): first-order covariance of both.
	EarlierFeatures inFrame(const Pose2& frame, const Eigen::Matrix3d& frame_cov) const;
};

/// Global features `points` (IDs `ids`) moved into the frame of the pose
/// `frame`, with the first-order covariance from `joint_cov`, the joint
/// covariance of [frame pose; points] in the global frame (3 + 2n square):
/// the frame's correlation with the features included, as in eq. 5.13.
EarlierFeatures earlierFeaturesInFrame(const Pose2& frame, const std::vector<LandmarkId>& ids,
									   const std::vector<Eigen::Vector2d>& points, const Eigen::MatrixXd& joint_cov);

}  // namespace esif
