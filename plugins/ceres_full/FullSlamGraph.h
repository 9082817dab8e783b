#pragma once
/// \file FullSlamGraph.h
/// The full-SLAM problem of book Sec. 1.2.2.2 as a Ceres problem: every robot
/// pose and every landmark is a parameter block, every odometry increment and
/// every range-bearing measurement a residual block (eq. 1.18-1.21). The
/// first pose is the origin of the map frame and held constant (the gauge).
/// It also keeps the block structure of J, to report the non-zeros of the
/// information matrix J^T J (book Table 5.1) without forming it.

#include <esif/core/StepInput.h>
#include <esif/models/Se2.h>

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <deque>
#include <memory>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace esif::ceres_full
{
/// One range-bearing term as added: which pose saw which landmark at what
/// range, through which sensor mounting (for checks of the solution).
struct ObservationRecord
{
	std::size_t pose = 0;
	LandmarkId landmark = 0;
	double range_m = 0;
	double range_std_m = 0;	 ///< standard deviation of the range [m]
	Pose2 sensor_on_robot = Pose2::Zero();
	ceres::ResidualBlockId block = nullptr;	 ///< null once dropped
};

/// An observation removed as an outlier: its index into observations() and
/// its squared whitened residual when it was removed (NaN: not evaluable).
struct DroppedObservation
{
	std::size_t index = 0;
	double chi2 = 0;
};

class FullSlamGraph
{
   public:
	/// `loss` (may be null) is applied to every range-bearing term; the graph
	/// keeps ownership of it.
	explicit FullSlamGraph(std::unique_ptr<ceres::LossFunction> loss = nullptr);

	/// Replaces the loss of every range-bearing term (null: plain least squares).
	void setObservationLoss(std::unique_ptr<ceres::LossFunction> loss);

	/// Squared whitened residual of observation `i` at the current values,
	/// without the loss; NaN when it cannot be evaluated.
	double observationChi2(std::size_t i) const;

	/// The remaining range-bearing terms whose observationChi2 is above
	/// `bound` (a term that cannot be evaluated is not among them: that is a
	/// collapsed solution, not an outlier).
	std::vector<DroppedObservation> observationsAbove(double bound) const;

	/// Removes the terms `dropped`, and a landmark left without any term.
	void dropObservations(const std::vector<DroppedObservation>& dropped);

	/// Range-bearing terms in the problem (not dropped).
	std::size_t liveObservations() const { return live_observations_; }

	/// Adds pose `from` (+) odometry as a new pose, initialised at `initial`,
	/// and its process-model term. Returns the new pose's index. Throws
	/// InputError naming `where` when the odometry covariance is not SPD.
	std::size_t addPose(std::size_t from, const OdometryIncrement& odometry, const Pose2& initial,
						const std::string& where);

	bool hasLandmark(LandmarkId id) const { return landmark_index_.count(id) > 0; }
	void addLandmark(LandmarkId id, const Eigen::Vector2d& initial);

	/// Adds the range-bearing term of `m` taken at pose `pose` of landmark
	/// `id` (already added). Throws NumericalError naming `where` when the
	/// measurement covariance is not SPD.
	void addObservation(std::size_t pose, LandmarkId id, const RangeBearing& m, const Pose2& sensor_on_robot,
						const std::string& where);

	std::size_t poseCount() const { return poses_.size(); }
	/// Every range-bearing term in the order added (dropped ones with a null block).
	const std::vector<ObservationRecord>& observations() const { return observations_; }
	std::size_t landmarkCount() const { return landmark_ids_.size(); }
	/// IDs of the landmarks in the problem, in the order they were first seen.
	const std::vector<LandmarkId>& landmarkIds() const { return landmark_ids_; }

	Pose2 pose(std::size_t i) const { return Eigen::Map<const Eigen::Vector3d>(poses_[i].data()); }
	Eigen::Vector2d landmark(LandmarkId id) const;
	void setPose(std::size_t i, const Pose2& p);

	double* poseBlock(std::size_t i) { return poses_[i].data(); }
	const double* poseBlock(std::size_t i) const { return poses_[i].data(); }
	double* landmarkBlock(LandmarkId id) { return landmarks_[landmark_index_.at(id)].data(); }
	const double* landmarkBlock(LandmarkId id) const { return landmarks_[landmark_index_.at(id)].data(); }
	/// True for the gauge pose (index 0), which is not estimated.
	static bool isGauge(std::size_t pose) { return pose == 0; }

	ceres::Problem& problem() { return *problem_; }
	/// The loss on range-bearing terms (a wrapper: plain least squares when it holds none).
	const ceres::LossFunction* loss() const { return loss_.get(); }

	/// Residual count m and estimated-parameter count n: at the optimum of
	/// the plain least-squares problem, 2 x cost ~ chi-square(m - n).
	std::size_t residualDim() const { return residual_dim_; }
	std::size_t parameterDim() const { return 3 * (poses_.size() - 1) + 2 * landmark_ids_.size(); }

	/// Sum of squared whitened residuals at the current values, without the
	/// robust loss: chi-square(m - n) at the optimum when the noise model is
	/// right. NaN when a residual cannot be evaluated.
	double plainChi2(int threads);

	/// Non-zeros of J^T J over the estimated blocks (both triangles): each
	/// block's square plus twice every distinct pair of blocks that share a
	/// residual (pose-pose links from odometry, pose-feature links from
	/// observations; a link is kept when its last term was dropped, an
	/// overcount of at most one 3x2 block per dropped measurement).
	std::size_t informationNonZeros() const;

	/// J^T J at the current values, over the estimated blocks: poses 1..N,
	/// then landmarks in first-seen order. Evaluates every residual; throws
	/// NumericalError when a derivative is not finite.
	Eigen::SparseMatrix<double> informationMatrix(int threads);

   private:
	void linkBlocks(const double* a, int dim_a, const double* b, int dim_b);

	void removeLandmark(LandmarkId id);

	std::unique_ptr<ceres::LossFunctionWrapper> loss_;
	std::unique_ptr<ceres::Problem> problem_;
	// deques: parameter blocks must never move once Ceres holds their address.
	std::deque<std::array<double, 3>> poses_;
	std::deque<std::array<double, 2>> landmarks_;
	std::unordered_map<LandmarkId, std::size_t> landmark_index_;
	std::vector<LandmarkId> landmark_ids_;
	std::vector<ObservationRecord> observations_;
	std::size_t live_observations_ = 0;
	std::size_t residual_dim_ = 0;

	struct PairHash
	{
		std::size_t operator()(const std::pair<const double*, const double*>& p) const
		{
			return std::hash<const double*>()(p.first) * 31 + std::hash<const double*>()(p.second);
		}
	};
	std::unordered_set<std::pair<const double*, const double*>, PairHash> linked_;
	std::size_t off_diagonal_nnz_ = 0;	///< one triangle
};

}  // namespace esif::ceres_full
