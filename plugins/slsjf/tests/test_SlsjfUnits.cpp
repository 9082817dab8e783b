// SLSJF (book Ch. 5) on inputs whose answer is known exactly: one local map
// is the global map; noise-free local maps give the truth, with the start
// of each map shared with the previous end pose or linked to it by
// odometry (eq. 5.4-5.6), with landmark IDs and with JCBB association; the
// virtual observation marginalises left-out features exactly.

#include <EsifTestSupport.h>
#include <LocalMapTestSupport.h>

#include "VirtualObservation.h"

#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/eval/Evaluator.h>
#include <esif/formats/GroundTruth.h>
#include <esif/plugin/LocalMapJoiner.h>
#include <esif/sim/Scenario.h>
#include <esif/sim/Simulator.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>


namespace
{
using namespace esif;

LocalMapJoiner& joinerOf(FilterPlugin& plugin)
{
	auto* joiner = dynamic_cast<LocalMapJoiner*>(&plugin);
	if (!joiner) throw std::logic_error("Slsjf is not a LocalMapJoiner");
	return *joiner;
}

TEST(SlsjfUnits, OneLocalMapIsTheGlobalMap)
{
	// Algorithm 5.1, k = 1: "the first local map is set as the global map".
	auto plugin = test::makePlugin("Slsjf", "");
	const LocalMap map = test::randomLocalMap(1, 4, 7);
	joinerOf(*plugin).joinLocalMap(map);
	plugin->finish();

	const Eigen::MatrixXd P = map.information.inverse();  // 11 x 11 reference
	const Estimate e = plugin->estimate();
	ASSERT_EQ(e.landmarks.size(), 4u);
	for (std::size_t i = 0; i < 4; ++i)
	{
		EXPECT_EQ(e.landmarks[i].id, map.features[i].id);
		EXPECT_LT((e.landmarks[i].mean - map.features[i].position).norm(), 1e-10);
		EXPECT_LT((e.landmarks[i].cov - P.block<2, 2>(3 + 2 * i, 3 + 2 * i)).norm(), 1e-10 * P.norm());
	}
	const auto ends = joinerOf(*plugin).endPoses();
	ASSERT_EQ(ends.size(), 1u);
	EXPECT_LT((ends[0].mean - map.end_pose).norm(), 1e-10);
	EXPECT_LT((ends[0].cov - P.topLeftCorner<3, 3>()).norm(), 1e-10 * P.norm());

	const CostFigures cost = plugin->costFigures();
	EXPECT_EQ(cost.state_dim, 11u);
	EXPECT_EQ(cost.poses_in_state, 1u);
	EXPECT_EQ(cost.info_nnz, 121u);	 // one dense 11 x 11 block
	EXPECT_EQ(joinerOf(*plugin).mapReport(1).associations.size(), 4u);
}

TEST(SlsjfUnits, MapsMustComeInOrder)
{
	auto plugin = test::makePlugin("Slsjf", "");
	EXPECT_THROW(joinerOf(*plugin).joinLocalMap(test::randomLocalMap(2, 2, 1)), InputError);
}

TEST(SlsjfUnits, LeftOutFeaturesAreMarginalisedExactly)
{
	// The kept part of the virtual observation must carry the marginal of
	// the local map over it: its covariance is the kept block of P.
	const LocalMap map = test::randomLocalMap(3, 5, 11);
	const auto obs = slsjf::keepFeatures(map, {true, false, true, false, true});
	ASSERT_EQ(obs.kept, (std::vector<std::size_t>{0, 2, 4}));
	const Eigen::MatrixXd P = map.information.inverse();
	const std::vector<Eigen::Index> rows = {0, 1, 2, 3, 4, 7, 8, 11, 12};
	const Eigen::MatrixXd expected = P(rows, rows);
	EXPECT_LT((obs.information.inverse() - expected).norm(), 1e-10 * expected.norm());
	EXPECT_EQ(obs.z(5), map.features[2].position.x());
	EXPECT_LT((map.covarianceMatrix() - P).norm(), 1e-10 * P.norm());
}

/// A noise-free run of configs/sim/small.ini; the filters are told a small
/// noise (zero measurement noise would make the EKF's innovation covariance
/// singular), so every innovation is zero and the estimate must be the truth.
struct NoiseFree
{
	test::TempDir dir;
	Rawlog log;
	GroundTruth truth;

	NoiseFree()
	{
		Scenario s = test::loadScenario("configs/sim/small.ini");
		s.std_range_m = s.std_bearing_deg = s.std_speed_mps = s.std_turn_rate_deg_s = 0;
		Simulator(s).writeRawlog(dir.file("free.rawlog"));
		RawlogReadOptions options;
		options.sensor_std_range_m = 0.01;
		options.sensor_std_bearing_rad = 0.1 * M_PI / 180;
		log = readRawlog(dir.file("free.rawlog"), options);
		truth = loadGroundTruth(groundTruthPrefixFor(dir.file("free.rawlog")))->inInitialPoseFrame();
	}

	/// Largest landmark and end-pose position error of a run of `section`.
	std::pair<double, double> largestErrors(const std::string& section, bool hide_ids = false)
	{
		Rawlog input = log;
		if (hide_ids)
			for (auto& step : input.steps)
				if (step.scan)
					for (auto& m : step.scan->measurements) m.id.reset();
		auto plugin = test::makePlugin("Slsjf", section);
		const ReplayResult r = replay(*plugin, input, {0, false});
		const auto filter_to_true = r.audit.filterToTrue();
		EXPECT_EQ(r.audit.wrongCount(), 0u) << section;
		double landmark = 0, pose = 0;
		for (const auto& lm : r.record.final_estimate.landmarks)
			landmark = std::max(landmark, (lm.mean - truth.landmarks.at(filter_to_true.at(lm.id))).norm());
		for (const auto& tp : r.record.trajectory)
			pose = std::max(pose, (tp.pose.mean.head<2>() - truth.path[tp.step].head<2>()).norm());
		EXPECT_GT(r.record.final_estimate.landmarks.size(), 10u) << section;
		return {landmark, pose};
	}
};

// The rawlog stores ranges and bearings as 32-bit floats (MRPT's
// CObservationBearingRange): a relative 6e-8, so up to 3e-7 m at the 5 m
// range, and the estimate inherits errors of that size (measured: 1.9e-7 m,
// whatever the map size or smoothing). 2e-6 m is above that floor and four
// orders below the noise the filters are told (1 cm): a modelling error of
// any size would show.
constexpr double kExact = 2e-6;

/// A local map in the frame of its start pose with features of the given
/// IDs and positions, all known to 1 mm (information 1e6 per coordinate).
LocalMap preciseMap(std::size_t index, const std::vector<std::pair<LandmarkId, Eigen::Vector2d>>& features)
{
	LocalMap map;
	map.index = index;
	map.end_pose = Pose2(1, 0, 0);
	for (const auto& [id, xy] : features) map.features.push_back({id, xy, index > 1});
	const auto d = static_cast<Eigen::Index>(3 + 2 * features.size());
	map.information = 1e6 * Eigen::MatrixXd::Identity(d, d);
	return map;
}

TEST(SlsjfUnits, TheIdGateTestsEachMatchUnderBothMapsCovariances)
{
	// Map 2 starts at map 1's end pose, (1, 0, 0), through an odometry link
	// whose heading is uncertain to 0.1 rad: a feature 10 m away is then
	// uncertain by about 1 m across, in map 2's frame, while each map knows
	// its features to 1 mm. The 0.9999 gate (2 dof) is 4.3 sigma.
	auto plugin = test::makePlugin("Slsjf", "association = known_ids\nid_gate_chi2_quantile = 0.9999\n");
	joinerOf(*plugin).joinLocalMap(
		preciseMap(1, {{10, Eigen::Vector2d(10, 0)}, {11, Eigen::Vector2d(1, 10)}, {12, Eigen::Vector2d(10, 10)}}));
	// In map 2's frame: 10 at (9, 0), 11 at (0, 10), 12 at (9, 10).
	LocalMap second = preciseMap(2, {{10, Eigen::Vector2d(9, 0.0005)},  // inside the gate of the local 1 mm alone
									 {11, Eigen::Vector2d(0.5, 10)},     // 500 sigma of 1 mm, 0.5 sigma of the heading
									 {12, Eigen::Vector2d(39, 10)}});     // 30 m off: outside under both
	second.link = OdometryIncrement{Pose2::Zero(), Eigen::Vector3d(1e-6, 1e-6, 0.01).asDiagonal()};
	joinerOf(*plugin).joinLocalMap(second);

	const StepReport report = joinerOf(*plugin).mapReport(2);
	ASSERT_EQ(report.associations.size(), 3u);
	EXPECT_EQ(report.associations[0].kind, Association::Kind::Matched);
	EXPECT_EQ(report.associations[0].id, 10);
	EXPECT_EQ(report.associations[1].kind, Association::Kind::Matched);
	EXPECT_EQ(report.associations[1].id, 11);
	EXPECT_EQ(report.associations[2].kind, Association::Kind::Rejected);
}

TEST(SlsjfUnits, NoiseFreeMapsGiveTheTruth)
{
	NoiseFree free;
	for (const char* section :
		 {"association = known_ids\nlocal_map_steps = 20\n", "association = known_ids\nlocal_map_steps = 7\nsmoothing = final\n",
		  "association = known_ids\nlocal_map_steps = 20\nlocal_map_link = odometry\n"})
	{
		const auto [landmark, pose] = free.largestErrors(section);
		EXPECT_LT(landmark, kExact) << section;
		EXPECT_LT(pose, kExact) << section;
	}
}

TEST(SlsjfUnits, NoiseFreeMapsAssociatedByJcbbGiveTheTruth)
{
	NoiseFree free;
	const auto [landmark, pose] = free.largestErrors("association = jcbb\nlocal_association = jcbb\nlocal_map_steps = 20\n", true);
	EXPECT_LT(landmark, kExact);
	EXPECT_LT(pose, kExact);
}

}  // namespace
