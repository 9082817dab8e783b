#include "FullSlamGraph.h"

#include "QuietCeresLogging.h"
#include "Residuals.h"

#include <esif/core/Errors.h>

#include <algorithm>
#include <cmath>

namespace esif::ceres_full
{
namespace
{
ceres::Problem::Options problemOptions()
{
	ceres::Problem::Options o;
	o.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;  // the graph owns its one loss
	// Only outliers are removed, few and once: no per-block removal index.
	o.enable_fast_removal = false;
	return o;
}
}  // namespace

FullSlamGraph::FullSlamGraph(std::unique_ptr<ceres::LossFunction> loss)
	: loss_(std::make_unique<ceres::LossFunctionWrapper>(loss.release(), ceres::TAKE_OWNERSHIP)),
	  problem_(std::make_unique<ceres::Problem>(problemOptions()))
{
	poses_.push_back({0, 0, 0});
	problem_->AddParameterBlock(poses_.back().data(), 3);
	problem_->SetParameterBlockConstant(poses_.back().data());	// the gauge: the map frame
}

std::size_t FullSlamGraph::addPose(
	std::size_t from, const OdometryIncrement& odometry, const Pose2& initial, const std::string& where)
{
	Eigen::Matrix3d w;
	if (!sqrtInformation<3>(odometry.cov, w))
		throw NumericalError(where + ": covariance is not symmetric positive definite");
	poses_.push_back({initial.x(), initial.y(), esif::wrapAngle(initial.z())});
	double* added = poses_.back().data();
	problem_->AddResidualBlock(OdometryResidual::create(odometry.delta, w), nullptr, poses_[from].data(), added);
	residual_dim_ += 3;
	linkBlocks(poses_[from].data(), isGauge(from) ? 0 : 3, added, 3);
	return poses_.size() - 1;
}

void FullSlamGraph::addLandmark(LandmarkId id, const Eigen::Vector2d& initial)
{
	landmark_index_.emplace(id, landmarks_.size());
	landmark_ids_.push_back(id);
	landmarks_.push_back({initial.x(), initial.y()});
	problem_->AddParameterBlock(landmarks_.back().data(), 2);
}

void FullSlamGraph::addObservation(
	std::size_t pose, LandmarkId id, const RangeBearing& m, const Pose2& sensor_on_robot, const std::string& where)
{
	Eigen::Matrix2d w;
	if (!sqrtInformation<2>(m.cov, w))
		throw NumericalError(where + ": covariance is not symmetric positive definite");
	double* lm = landmarkBlock(id);
	const ceres::ResidualBlockId block = problem_->AddResidualBlock(
		RangeBearingResidual::create(Eigen::Vector2d(m.range_m, m.bearing_rad), w, sensor_on_robot), loss_.get(),
		poses_[pose].data(), lm);
	residual_dim_ += 2;
	++live_observations_;
	observations_.push_back({pose, id, m.range_m, std::sqrt(m.cov(0, 0)), sensor_on_robot, block});
	linkBlocks(poses_[pose].data(), isGauge(pose) ? 0 : 3, lm, 2);
}

void FullSlamGraph::setObservationLoss(std::unique_ptr<ceres::LossFunction> loss)
{
	loss_->Reset(loss.release(), ceres::TAKE_OWNERSHIP);
}

double FullSlamGraph::observationChi2(std::size_t i) const
{
	double cost = 0;
	const QuietCeresLogging quiet;
	if (!observations_[i].block ||
		!problem_->EvaluateResidualBlock(observations_[i].block, false, &cost, nullptr, nullptr))
		return std::nan("");
	return 2 * cost;
}

std::vector<DroppedObservation> FullSlamGraph::observationsAbove(double bound) const
{
	std::vector<DroppedObservation> out;
	for (std::size_t i = 0; i < observations_.size(); ++i)
		if (observations_[i].block)
			if (const double chi2 = observationChi2(i); chi2 > bound) out.push_back({i, chi2});
	return out;
}

void FullSlamGraph::dropObservations(const std::vector<DroppedObservation>& dropped)
{
	for (const auto& d : dropped)
	{
		problem_->RemoveResidualBlock(observations_[d.index].block);
		observations_[d.index].block = nullptr;
		residual_dim_ -= 2;
		--live_observations_;
	}
	// A landmark whose every term was dropped is no longer estimated.
	std::unordered_map<LandmarkId, std::size_t> terms;
	for (const auto& o : observations_)
		if (o.block) ++terms[o.landmark];
	const std::vector<LandmarkId> ids = landmark_ids_;
	for (const LandmarkId id : ids)
		if (!terms.count(id)) removeLandmark(id);
}

void FullSlamGraph::removeLandmark(LandmarkId id)
{
	problem_->RemoveParameterBlock(landmarkBlock(id));
	landmark_ids_.erase(std::find(landmark_ids_.begin(), landmark_ids_.end(), id));
}

Eigen::Vector2d FullSlamGraph::landmark(LandmarkId id) const
{
	const auto& l = landmarks_[landmark_index_.at(id)];
	return {l[0], l[1]};
}

void FullSlamGraph::setPose(std::size_t i, const Pose2& p) { poses_[i] = {p.x(), p.y(), esif::wrapAngle(p.z())}; }

void FullSlamGraph::linkBlocks(const double* a, int dim_a, const double* b, int dim_b)
{
	if (dim_a == 0 || dim_b == 0) return;  // the gauge pose is not in the state
	const auto key = a < b ? std::make_pair(a, b) : std::make_pair(b, a);
	if (linked_.insert(key).second) off_diagonal_nnz_ += static_cast<std::size_t>(dim_a * dim_b);
}

double FullSlamGraph::plainChi2(int threads)
{
	ceres::Problem::EvaluateOptions options;
	options.apply_loss_function = false;
	options.num_threads = threads;
	double cost = 0;  // Ceres' cost: half the sum of squares
	const QuietCeresLogging quiet;
	if (!problem_->Evaluate(options, &cost, nullptr, nullptr, nullptr)) return std::nan("");
	return 2 * cost;
}

std::size_t FullSlamGraph::informationNonZeros() const
{
	const std::size_t diagonal = 9 * (poses_.size() - 1) + 4 * landmark_ids_.size();
	return diagonal + 2 * off_diagonal_nnz_;
}

Eigen::SparseMatrix<double> FullSlamGraph::informationMatrix(int threads)
{
	ceres::Problem::EvaluateOptions options;
	for (std::size_t i = 1; i < poses_.size(); ++i) options.parameter_blocks.push_back(poseBlock(i));
	for (const LandmarkId id : landmark_ids_) options.parameter_blocks.push_back(landmarkBlock(id));
	options.apply_loss_function = true;
	options.num_threads = threads;
	ceres::CRSMatrix crs;
	const QuietCeresLogging quiet;
	if (!problem_->Evaluate(options, nullptr, nullptr, nullptr, &crs))
		throw NumericalError("the Jacobian cannot be evaluated (a pose sits on a landmark)");
	const Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, int>> j(
		crs.num_rows, crs.num_cols, static_cast<int>(crs.values.size()), crs.rows.data(), crs.cols.data(),
		crs.values.data());
	return Eigen::SparseMatrix<double>(j.transpose()) * Eigen::SparseMatrix<double>(j);
}

}  // namespace esif::ceres_full
