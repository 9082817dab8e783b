#pragma once
/// \file LocalSlam.h
/// D-SLAM's first localisation process (book Sec. 3.1.4.3, Fig. 3.4 steps
/// A-B-C and D-E): EKF SLAM over the robot and only the features in view.
/// Features that leave the view are dropped (marginalised); one that comes
/// back is initialised again from its measurement, never from the map, so
/// this estimate stays independent of the map's information.
///
/// Beyond the book, a feature out of view may be held for `hold_steps`
/// odometry steps after its last sighting (0 = dropped at once, the book).
/// It stays as independent of the map: only odometry and the scans' own
/// measurements inform it. Why: on Victoria Park a tree is missed by one
/// scan and seen by the next for 39% of its re-sightings (gap of 2-10
/// steps); dropped at once, it comes back with no memory of where it was,
/// and the robot drifts on odometry until two mapped trees are in view
/// (docs/plugins/dslam.md, "Holding features out of view").

#include <esif/core/StepInput.h>
#include <esif/ekf/EkfSlamCore.h>

#include <optional>
#include <unordered_map>
#include <vector>

namespace esif::dslam
{
/// A measurement with the feature it was associated with.
struct IdentifiedMeasurement
{
	LandmarkId id = 0;
	Eigen::Vector2d z;  ///< (range, bearing)
	Eigen::Matrix2d R;
};

class LocalSlam
{
   public:
	explicit LocalSlam(int hold_steps = 0) : hold_steps_(hold_steps) {}

	/// Step A -> B, eq. (3.19).
	void predict(const OdometryIncrement& u)
	{
		ekf_.predict(u);
		++steps_;
	}

	/// Step B -> C: drops the features not in `seen` (with hold_steps, those
	/// not seen for more than hold_steps predictions), updates with the
	/// measurements of the features it kept, and initialises the other
	/// features of `seen` from their measurements (re-observed features come
	/// back this way, never from the map).
	void observe(const std::vector<IdentifiedMeasurement>& seen, const Pose2& sensor_on_robot);

	/// Keeps only the features `order` (all held), in that order: the layout
	/// of the kidnapped-robot state for the fusion (step C).
	void arrange(const std::vector<LandmarkId>& order);
	/// Moves the features `order` (all held) to the front, in that order,
	/// and keeps the others after them: the fused state's layout when
	/// features out of view are held.
	void bringToFront(const std::vector<LandmarkId>& order);

	/// Step E: adds features seen for the first time.
	void addFeatures(const std::vector<IdentifiedMeasurement>& fresh, const Pose2& sensor_on_robot);

	bool holds(LandmarkId id) const { return index_of_.count(id) > 0; }

	/// Squared Mahalanobis distance of the innovation of `m` against this
	/// EKF (S = H P H^T + R), or nothing when its feature is not held.
	std::optional<double> innovationDistance2(const IdentifiedMeasurement& m, const Pose2& sensor_on_robot) const;

	/// Predicted measurements of the held features order()[k] for k in
	/// `held` (rows in that order) and their joint covariance H P H^T + R,
	/// robot-feature correlations included, for a measurement noise `R`: the
	/// association input of the tracking stage (HeldFeatureTracking.h).
	struct HeldPrediction
	{
		Eigen::MatrixXd predictions;  ///< held.size() x 2 (range, bearing)
		Eigen::MatrixXd covariance;	  ///< 2 held.size() square
	};
	HeldPrediction predictHeld(const std::vector<std::size_t>& held, const Pose2& sensor_on_robot,
							   const Eigen::Matrix2d& R) const;

	/// Predicted measurement of the held feature order()[k] and its H P H^T
	/// (robot uncertainty included, no sensor noise): a diagonal block of
	/// predictHeld() without R, in constant time.
	struct FeaturePrediction
	{
		Eigen::Vector2d z;
		Eigen::Matrix2d covariance;
	};
	FeaturePrediction predictHeldFeature(std::size_t k, const Pose2& sensor_on_robot) const;

	/// State [robot; features in order()] and its covariance (step C).
	Eigen::VectorXd state() const { return ekf_.state(); }
	Eigen::MatrixXd covariance() const { return ekf_.covariance(); }
	/// Step D: the fused estimate replaces the state (same layout).
	void setState(const Eigen::VectorXd& x, const Eigen::MatrixXd& P) { ekf_.setState(x, P); }

	Pose2 robot() const { return ekf_.robot(); }
	Eigen::Matrix3d robotCov() const { return ekf_.robotCov(); }
	const std::vector<LandmarkId>& order() const { return ids_; }

   private:
	void reindex();

	int hold_steps_ = 0;
	long long steps_ = 0;  ///< predictions so far: the clock of hold_steps
	std::unordered_map<LandmarkId, long long> last_seen_;
	EkfSlamCore ekf_;
	std::vector<LandmarkId> ids_;  ///< landmark index -> feature
	std::unordered_map<LandmarkId, std::size_t> index_of_;
};

}  // namespace esif::dslam
