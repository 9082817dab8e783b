#include "AdmissibleChain.h"

namespace esif::dslam
{
void AdmissibleChain::restart(const std::vector<IdentifiedMeasurement>& root_scan, const Pose2& sensor_on_robot)
{
	ekf_ = EkfSlamCore();  // robot exactly at the root
	ids_.clear();
	index_of_.clear();
	root_is_map_frame_ = false;
	scans_ = 0;
	absorb(root_scan, sensor_on_robot);
}

void AdmissibleChain::predict(const OdometryIncrement& u) { ekf_.predict(u); }

void AdmissibleChain::absorb(const std::vector<IdentifiedMeasurement>& scan, const Pose2& sensor_on_robot)
{
	std::vector<EkfSlamCore::Match> matches;
	for (const auto& m : scan)
		if (index_of_.count(m.id)) matches.push_back({index_of_.at(m.id), m.z, m.R});
	ekf_.update(matches, sensor_on_robot);
	add(scan, sensor_on_robot);
	++scans_;
}

void AdmissibleChain::add(const std::vector<IdentifiedMeasurement>& scan, const Pose2& sensor_on_robot)
{
	for (const auto& m : scan)
		if (!index_of_.count(m.id))
		{
			index_of_[m.id] = ekf_.addLandmark(m.z, m.R, sensor_on_robot);
			ids_.push_back(m.id);
		}
}

relative::PointSet AdmissibleChain::features() const
{
	const auto n = static_cast<Eigen::Index>(2 * ids_.size());
	return {ekf_.state().tail(n), ekf_.covariance().bottomRightCorner(n, n)};
}

VirtualObservation AdmissibleChain::virtualObservation(const Pose2& sensor_on_robot) const
{
	VirtualObservation v;
	v.ids = ids_;
	std::vector<std::size_t> all(ids_.size());
	v.range_bearing.resize(2 * ids_.size());
	for (std::size_t i = 0; i < ids_.size(); ++i)
	{
		all[i] = i;
		v.range_bearing.segment<2>(2 * i) = ekf_.predictMeasurement(i, sensor_on_robot).z;
	}
	v.cov = ekf_.predictionCovariance(all, sensor_on_robot);
	return v;
}

}  // namespace esif::dslam
