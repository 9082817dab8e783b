#pragma once
/// \file FakeRawlog.h
/// A hand-made Rawlog for host tests: 1 m of odometry along x per step and,
/// per step, the landmark IDs of its measurements (nullopt: a measurement
/// without ID; no entry at all: an odometry-only step without scan).

#include <esif/formats/RawlogReader.h>

#include <mrpt/obs/CSensoryFrame.h>

#include <optional>
#include <string>
#include <vector>

namespace esif::test
{
using StepIds = std::optional<std::vector<std::optional<LandmarkId>>>;

inline Rawlog makeRawlog(const std::vector<StepIds>& steps, const std::string& path = "fake.rawlog")
{
	Rawlog log;
	log.path = path;
	log.has_odometry = true;
	for (std::size_t k = 0; k < steps.size(); ++k)
	{
		StepInput step;
		step.index = k;
		step.time_s = 0.1 * static_cast<double>(k);
		step.odometry = OdometryIncrement{Pose2(1, 0, 0), Eigen::Matrix3d::Identity() * 1e-4};
		std::vector<std::optional<LandmarkId>> ids;
		if (steps[k])
		{
			step.scan = Scan{};
			for (const auto& id : *steps[k])
			{
				RangeBearing m;
				m.range_m = 2;
				m.id = id;
				step.scan->measurements.push_back(m);
				ids.push_back(id);
			}
			log.measurement_count += ids.size();
		}
		log.frames.push_back(steps[k] ? std::make_shared<mrpt::obs::CSensoryFrame>() : nullptr);
		log.true_ids.push_back(ids);
		log.steps.push_back(step);
	}
	return log;
}

}  // namespace esif::test
