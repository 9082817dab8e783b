#include "LocalSlam.h"

#include <esif/models/Se2.h>

#include <Eigen/Cholesky>

#include <unordered_set>

namespace esif::dslam
{
void LocalSlam::observe(const std::vector<IdentifiedMeasurement>& seen, const Pose2& sensor_on_robot)
{
	std::unordered_set<LandmarkId> seen_ids;
	for (const auto& m : seen) seen_ids.insert(m.id);
	std::vector<LandmarkId> kept;
	for (LandmarkId id : ids_)
		if (seen_ids.count(id) || (hold_steps_ > 0 && steps_ - last_seen_.at(id) <= hold_steps_)) kept.push_back(id);
	for (LandmarkId id : seen_ids) last_seen_[id] = steps_;
	arrange(kept);	// marginalise what is out of view: delete rows and columns

	std::vector<EkfSlamCore::Match> matches;
	for (const auto& m : seen)
		if (holds(m.id)) matches.push_back({index_of_.at(m.id), m.z, m.R});
	ekf_.update(matches, sensor_on_robot);
	std::vector<IdentifiedMeasurement> returning;
	for (const auto& m : seen)
		if (!holds(m.id)) returning.push_back(m);
	addFeatures(returning, sensor_on_robot);
}

void LocalSlam::arrange(const std::vector<LandmarkId>& order)
{
	std::vector<std::size_t> keep;
	keep.reserve(order.size());
	for (LandmarkId id : order) keep.push_back(index_of_.at(id));
	ekf_.retainLandmarks(keep);
	ids_ = order;
	reindex();
	for (auto it = last_seen_.begin(); it != last_seen_.end();)
		it = holds(it->first) ? std::next(it) : last_seen_.erase(it);
}

void LocalSlam::bringToFront(const std::vector<LandmarkId>& order)
{
	std::unordered_set<LandmarkId> front(order.begin(), order.end());
	std::vector<LandmarkId> all = order;
	for (LandmarkId id : ids_)
		if (!front.count(id)) all.push_back(id);
	arrange(all);
}

void LocalSlam::addFeatures(const std::vector<IdentifiedMeasurement>& fresh, const Pose2& sensor_on_robot)
{
	for (const auto& m : fresh)
	{
		ekf_.addLandmark(m.z, m.R, sensor_on_robot);
		ids_.push_back(m.id);
		last_seen_[m.id] = steps_;
	}
	reindex();
}

std::optional<double> LocalSlam::innovationDistance2(const IdentifiedMeasurement& m,
													 const Pose2& sensor_on_robot) const
{
	const auto it = index_of_.find(m.id);
	if (it == index_of_.end()) return std::nullopt;
	const auto h = ekf_.predictMeasurement(it->second, sensor_on_robot);
	Eigen::Vector2d nu = m.z - h.z;
	nu(1) = wrapAngle(nu(1));
	const Eigen::Matrix2d S = ekf_.predictionCovariance({it->second}, sensor_on_robot) + m.R;
	return nu.dot(S.ldlt().solve(nu));
}

LocalSlam::HeldPrediction LocalSlam::predictHeld(const std::vector<std::size_t>& held, const Pose2& sensor_on_robot,
												  const Eigen::Matrix2d& R) const
{
	HeldPrediction out;
	out.predictions.resize(static_cast<Eigen::Index>(held.size()), 2);
	for (std::size_t i = 0; i < held.size(); ++i)
		out.predictions.row(static_cast<Eigen::Index>(i)) = ekf_.predictMeasurement(held[i], sensor_on_robot).z.transpose();
	out.covariance = ekf_.predictionCovariance(held, sensor_on_robot);
	for (std::size_t i = 0; i < held.size(); ++i) out.covariance.block<2, 2>(2 * i, 2 * i) += R;
	return out;
}

LocalSlam::FeaturePrediction LocalSlam::predictHeldFeature(std::size_t k, const Pose2& sensor_on_robot) const
{
	return {ekf_.predictMeasurement(k, sensor_on_robot).z, ekf_.predictionCovariance({k}, sensor_on_robot)};
}

void LocalSlam::reindex()
{
	index_of_.clear();
	for (std::size_t i = 0; i < ids_.size(); ++i) index_of_[ids_[i]] = i;
}

}  // namespace esif::dslam
