#pragma once
/// \file AdmissibleChain.h
/// Admissible measurements (book Sec. 3.4.1, Fig. 3.6). A scan that sees
/// fewer than two mapped features cannot be recast. The scans since the
/// last admissible one are then combined by a small EKF SLAM that starts,
/// exactly known, at that scan's pose (the chain's root): it fuses the
/// root's measurements, each odometry increment and each later scan. Its
/// estimate, turned into ranges and bearings from the current pose with
/// their full covariance, is the virtual observation that replaces the
/// withdrawn map update of the root scan.
///
/// Before any scan is admissible the root is the initial pose, i.e. the map
/// frame itself, and the chain's feature estimates are absolute.

#include "LocalSlam.h"

#include <esif/ekf/EkfSlamCore.h>
#include <esif/relative/RelativeGeometry.h>

#include <unordered_map>
#include <vector>

namespace esif::dslam
{
/// Ranges and bearings of every chain feature from the current pose, with
/// their joint covariance H P H^T (no further sensor noise: the chain's
/// estimate already holds it).
struct VirtualObservation
{
	std::vector<LandmarkId> ids;
	Eigen::VectorXd range_bearing;
	Eigen::MatrixXd cov;
};

class AdmissibleChain
{
   public:
	/// Starts at the initial pose: the root is the map frame.
	AdmissibleChain() = default;

	/// Starts a new chain rooted at the current pose with that scan's
	/// measurements (the last admissible scan).
	void restart(const std::vector<IdentifiedMeasurement>& root_scan, const Pose2& sensor_on_robot);

	void predict(const OdometryIncrement& u);

	/// Fuses an inadmissible scan: updates with re-observed chain features,
	/// adds the others.
	void absorb(const std::vector<IdentifiedMeasurement>& scan, const Pose2& sensor_on_robot);

	/// True while the root is the initial pose (no admissible scan yet).
	bool rootIsMapFrame() const { return root_is_map_frame_; }
	const std::vector<LandmarkId>& ids() const { return ids_; }
	/// Scans fused since the root, the root included.
	int scans() const { return scans_; }

	/// The chain's features in the root frame with their joint covariance.
	relative::PointSet features() const;
	/// The virtual observation from the current pose (the sensor at
	/// `sensor_on_robot`).
	VirtualObservation virtualObservation(const Pose2& sensor_on_robot) const;

   private:
	void add(const std::vector<IdentifiedMeasurement>& scan, const Pose2& sensor_on_robot);

	EkfSlamCore ekf_;
	std::vector<LandmarkId> ids_;
	std::unordered_map<LandmarkId, std::size_t> index_of_;
	bool root_is_map_frame_ = true;
	int scans_ = 0;
};

}  // namespace esif::dslam
