#pragma once
/// \file LocalMap.h
/// One local map of the map-joining filters (book Ch. 4 eq. 4.2-4.4, Ch. 5
/// eq. 5.1): an EKF SLAM map started from a robot pose with zero uncertainty
/// and expressed in that pose's frame. It holds the robot END pose and the
/// features, both in the local frame, with their joint information matrix.
///
/// Pose numbering follows the authors' local-map files: pose 0 is the global
/// origin (the start of map 1), pose k is the end of map k, and map k is
/// expressed in pose k-1 (its start pose). When `link` is set the start pose
/// is instead a pose of its own, reached from pose k-1 by a noisy odometry
/// increment (eq. 5.4); without it, start(k) = end(k-1) exactly, as in the
/// book's experiments and every published data set.

#include <esif/core/Estimate.h>
#include <esif/core/StepInput.h>
#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// One feature of a local map, in the map's (start-pose) frame.
struct LocalMapFeature
{
	LandmarkId id = 0;	///< identity (the rawlog's ID, or one given by the builder)
	Eigen::Vector2d position = Eigen::Vector2d::Zero();
	/// Known to be a feature of an earlier local map (by ID, or matched by the
	/// builder to a feature of the previous map): the book's Ch. 4 rule needs
	/// at least two such features per map (Sec. 4.4.4).
	bool in_earlier_maps = false;
};

struct LocalMap
{
	std::size_t index = 0;	///< k = 1, 2, ...
	Pose2 end_pose = Pose2::Zero();	 ///< robot end pose in the local frame (x, y, phi wrapped)
	std::vector<LocalMapFeature> features;
	/// Information matrix of the state [end pose (3); features (2 each)], in
	/// that order: (3 + 2n) square, symmetric positive definite.
	Eigen::MatrixXd information;
	/// Its covariance, when the map was built here (EKF form); files hold
	/// the information only.
	std::optional<Eigen::MatrixXd> covariance;
	/// Whether equal feature IDs mean one feature across maps (the input's
	/// landmark IDs, as in the authors' files). False when the IDs are only
	/// labels: features the builder numbered itself, or IDs the host hid.
	/// A joining filter must then associate the features itself.
	bool ids_identify_features = true;
	/// Odometry from pose k-1 to this map's start pose, with its covariance
	/// (eq. 5.4). nullopt: the start pose is pose k-1 itself.
	std::optional<OdometryIncrement> link;

	/// Host steps covered (first and last step index of the rawlog), and the
	/// measurements fused: zero when read from files.
	std::size_t first_step = 0;
	std::size_t last_step = 0;
	std::size_t steps = 0;
	std::size_t measurements = 0;
	/// The association of every measurement of those steps, by this map's
	/// feature IDs (empty when read from files).
	std::vector<StepReport> step_reports;

	/// Dimension of the state: 3 + 2 * features.
	std::size_t stateDim() const { return 3 + 2 * features.size(); }
	/// The state vector [end pose; x1, y1, ...] the information matrix is about.
	Eigen::VectorXd state() const;
	/// The covariance of the state: the map's own when it has one (built
	/// here), else its information inverted by Cholesky (a local map is
	/// small: at most a few hundred scalars). Throws NumericalError naming
	/// the map when the information is not positive definite.
	Eigen::MatrixXd covarianceMatrix() const;
	/// Features whose `in_earlier_maps` flag is set.
	std::size_t featuresInEarlierMaps() const;

	/// Checks sizes, finiteness, distinct feature IDs, symmetry (to
	/// `symmetry_tolerance` relative to the largest entry) and positive
	/// definiteness of the information (and covariance, if any). Throws
	/// NumericalError "`origin`: local map k: ..." naming the problem.
	void validate(const std::string& origin, double symmetry_tolerance = 1e-9) const;
};

}  // namespace esif
