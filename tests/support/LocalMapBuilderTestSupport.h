#pragma once
/// \file LocalMapBuilderTestSupport.h
/// Helpers of the local-map builder tests: simulated runs kept in memory (no
/// float rounding of the rawlog), the builder run over a whole step
/// sequence, and the true geometry of a local map (features and end pose in
/// its start frame).

#include <esif/config/ConfigFile.h>
#include <esif/localmap/LocalMapBuilder.h>
#include <esif/models/LocalMapObservation.h>
#include <esif/models/Se2.h>
#include <esif/sim/Scenario.h>
#include <esif/sim/Simulator.h>

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace esif::test::builder
{
/// A simulated run held in memory: the steps a filter sees, and the truth.
struct SimulatedRun
{
	std::vector<StepInput> steps;
	std::vector<Pose2> true_poses;	///< true pose of each step (world frame)
	std::map<LandmarkId, Eigen::Vector2d> features;	 ///< true features (world frame)
};

/// The [simulation] section of configs/sim/NAME.ini.
inline Scenario scenarioFromConfig(const std::string& name)
{
	return Scenario::fromConfig(ConfigFile::load(std::string(ESIF_SOURCE_DIR) + "/configs/sim/" + name + ".ini"));
}

/// The scenario without any noise (exact odometry and measurements).
inline Scenario withoutNoise(Scenario s)
{
	s.std_range_m = s.std_bearing_deg = s.std_speed_mps = s.std_turn_rate_deg_s = 0;
	return s;
}

/// Runs `scenario` in memory. When `filter_std_range_m` > 0 every
/// measurement's covariance is replaced by diag(range^2, bearing^2), as
/// RawlogReadOptions::sensor_std_* does for a rawlog: a noise-free scenario
/// needs a small nonzero filter noise (a zero measurement covariance makes
/// the EKF's innovation covariance singular).
inline SimulatedRun simulateInMemory(
	const Scenario& scenario, double filter_std_range_m = 0, double filter_std_bearing_rad = 0)
{
	const Simulator sim(scenario);
	SimulatedRun run;
	for (std::size_t i = 0; i < sim.features().size(); ++i) run.features[sim.featureIds()[i]] = sim.features()[i];
	sim.simulate([&](const SimulatedStep& s) {
		StepInput in = s.input;
		if (filter_std_range_m > 0 && in.scan)
			for (auto& m : in.scan->measurements)
				m.cov = Eigen::Vector2d(
							filter_std_range_m * filter_std_range_m, filter_std_bearing_rad * filter_std_bearing_rad)
							.asDiagonal();
		run.steps.push_back(std::move(in));
		run.true_poses.push_back(s.true_pose);
	});
	return run;
}

/// What the builder produced over a whole step sequence.
struct BuiltMaps
{
	std::vector<LocalMap> maps;	 ///< closed maps in order, the one finish() emitted last
	std::vector<StepReport> provisional_reports;  ///< processStep()'s return, one per step
	bool last_from_finish = false;	///< whether finish() emitted a map
};

inline BuiltMaps buildLocalMaps(const LocalMapBuilderParams& params, const std::vector<StepInput>& steps)
{
	LocalMapBuilder builder(params);
	BuiltMaps out;
	for (const auto& step : steps)
	{
		out.provisional_reports.push_back(builder.processStep(step));
		if (auto m = builder.takeClosedMap()) out.maps.push_back(std::move(*m));
	}
	if (auto m = builder.finish())
	{
		out.maps.push_back(std::move(*m));
		out.last_from_finish = true;
	}
	return out;
}

/// The true start pose (world frame) of each map, in the builder's
/// convention: map 1 starts at the pose of its first step (whose odometry is
/// the simulator's zero move, or none); map k >= 2 at the previous map's last
/// step (shared pose) or, with an odometry link, at its own first step.
inline std::vector<Pose2> trueStartPoses(const std::vector<LocalMap>& maps, const std::vector<Pose2>& true_poses)
{
	std::vector<Pose2> out;
	for (std::size_t k = 0; k < maps.size(); ++k)
	{
		if (k == 0)
			out.push_back(true_poses.at(maps[0].first_step));
		else if (maps[k].link)
			out.push_back(true_poses.at(maps[k].first_step));
		else
			out.push_back(true_poses.at(maps[k - 1].last_step));
	}
	return out;
}

/// A world point in the frame of `start`.
inline Eigen::Vector2d inFrame(const Pose2& start, const Eigen::Vector2d& world)
{
	return pointInFrame(start, world).value;
}

/// The true landmark ID of every feature of `map`, from its step reports and
/// the true IDs of each step's measurements (`true_ids[step][measurement]`);
/// features whose reports disagree on the true ID map to -2.
template <class TrueIds>
std::map<LandmarkId, LandmarkId> trueIdsOfFeatures(const LocalMap& map, const TrueIds& true_ids)
{
	std::map<LandmarkId, LandmarkId> out;
	for (std::size_t s = 0; s < map.step_reports.size(); ++s)
	{
		const auto& assoc = map.step_reports[s].associations;
		const auto& truth = true_ids.at(map.first_step + s);
		for (std::size_t i = 0; i < assoc.size(); ++i)
		{
			if (assoc[i].kind == Association::Kind::Rejected || !truth.at(i)) continue;
			const auto [it, inserted] = out.emplace(assoc[i].id, *truth.at(i));
			if (!inserted && it->second != *truth.at(i)) it->second = -2;
		}
	}
	return out;
}

}  // namespace esif::test::builder
