// The replay loop on local maps with the test joiner: end poses composed in
// order, features placed in the global frame, reports per map audited
// against the files' IDs; hidden IDs renumbered for the plugin yet scored
// against the files; plugin bugs named as such.

#include <DeadReckoningJoiner.h>
#include <FakePlugin.h>
#include <LocalMapTestSupport.h>

#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/localmaps/LocalMapReplay.h>

#include <gtest/gtest.h>

#include <cmath>
#include <new>

namespace
{
using esif::Association;
using esif::Pose2;
using esif::test::DeadReckoningJoiner;
using esif::test::makeLocalMap;

const esif::LocalMapReplayOptions kShown{false, false};
const esif::LocalMapReplayOptions kHidden{true, false};

/// Map 1 (global frame): end (1, 0, 90 deg), feature 1 at (2, 1). Map 2
/// (frame of that end pose): feature 1 again, seen at (1, -1), feature 2 at
/// (0, 2), i.e. globally (-1, 0); end (1, 0, 0), i.e. globally (1, 1, 90 deg).
std::vector<esif::LocalMap> twoMaps()
{
	return {makeLocalMap(1, Pose2(1, 0, M_PI / 2), {{1, 2, 1}}),
			makeLocalMap(2, Pose2(1, 0, 0), {{1, 1, -1}, {2, 0, 2}})};
}

void configure(DeadReckoningJoiner& joiner, const std::string& section_text)
{
	const auto cfg = esif::ConfigFile::fromText("[dead_reckoning_joiner]\n" + section_text, "test.ini");
	joiner.configure(cfg.section("dead_reckoning_joiner"));
}

const esif::LandmarkEstimate* landmark(const esif::Estimate& e, esif::LandmarkId id)
{
	for (const auto& lm : e.landmarks)
		if (lm.id == id) return &lm;
	return nullptr;
}

TEST(LocalMapReplay, ComposesEndPosesAndPlacesFeaturesInTheGlobalFrame)
{
	DeadReckoningJoiner joiner;
	const auto result = esif::replayLocalMaps(joiner, twoMaps(), "maps", kShown);
	ASSERT_EQ(result.record.trajectory.size(), 2u);
	EXPECT_EQ(result.record.trajectory[0].step, 1u);
	EXPECT_DOUBLE_EQ(result.record.trajectory[1].time_s, 2.0);
	const auto& end2 = result.record.trajectory[1].pose.mean;
	EXPECT_NEAR(end2.x(), 1.0, 1e-12);
	EXPECT_NEAR(end2.y(), 1.0, 1e-12);
	EXPECT_NEAR(end2(2), M_PI / 2, 1e-12);
	EXPECT_GT(result.record.trajectory[1].pose.cov(0, 0), result.record.trajectory[0].pose.cov(0, 0));
	ASSERT_EQ(result.record.keyframes.size(), 2u);	// the end poses, for map.simplemap

	const auto* l1 = landmark(result.record.final_estimate, 1);
	const auto* l2 = landmark(result.record.final_estimate, 2);
	ASSERT_TRUE(l1 && l2);
	EXPECT_NEAR((l1->mean - Eigen::Vector2d(2, 1)).norm(), 0.0, 1e-12);
	EXPECT_NEAR((l2->mean - Eigen::Vector2d(-1, 0)).norm(), 0.0, 1e-12);

	ASSERT_EQ(result.reports.size(), 2u);
	EXPECT_EQ(result.reports[0].associations[0].kind, Association::Kind::New);
	EXPECT_EQ(result.reports[1].associations[0].kind, Association::Kind::Matched);
	EXPECT_EQ(result.reports[1].associations[1].kind, Association::Kind::New);
	EXPECT_EQ(result.audit.newCount(), 2u);
	EXPECT_EQ(result.audit.matchedCount(), 1u);
	EXPECT_EQ(result.audit.wrongCount(), 0u);
	EXPECT_EQ(result.join_us.size(), 2u);
	ASSERT_EQ(result.fusion_costs.size(), 2u);
	EXPECT_EQ(result.fusion_costs[1].state_dim, 3u * 2 + 2u * 2);
}

TEST(LocalMapReplay, HiddenIdsAreRenumberedPerMapEntry)
{
	auto maps = twoMaps();
	maps[1].features[0].in_earlier_maps = true;
	const auto hidden = esif::withHiddenFeatureIds(maps);
	EXPECT_EQ(hidden[0].features[0].id, 1);
	EXPECT_EQ(hidden[1].features[0].id, 2);	 // file ID 1 again, another number
	EXPECT_EQ(hidden[1].features[1].id, 3);
	EXPECT_FALSE(hidden[1].features[0].in_earlier_maps);
	EXPECT_FALSE(hidden[1].ids_identify_features);
	EXPECT_TRUE(maps[1].ids_identify_features);
	EXPECT_EQ(maps[1].features[0].id, 1);  // the input is untouched
}

TEST(LocalMapReplay, HiddenIdsAreScoredAgainstTheFilesIds)
{
	// By ID the plugin cannot tell the two sightings of landmark 1 apart:
	// three landmarks, of which one splits file landmark 1.
	DeadReckoningJoiner by_id;
	const auto split = esif::replayLocalMaps(by_id, twoMaps(), "maps", kHidden);
	EXPECT_EQ(by_id.idsSeen(), (std::vector<std::vector<esif::LandmarkId>>{{1}, {2, 3}}));
	EXPECT_EQ(split.record.final_estimate.landmarks.size(), 3u);
	EXPECT_EQ(split.audit.newCount(), 3u);
	EXPECT_EQ(split.audit.wrongCount(), 1u);
	EXPECT_EQ(split.audit.filterToTrue().at(2), 1);	 // the plugin's landmark 2 is file landmark 1

	// Associating by position, it finds the match itself, and is scored right.
	DeadReckoningJoiner nearest;
	configure(nearest, "match_distance_m = 0.5\n");
	const auto joined = esif::replayLocalMaps(nearest, twoMaps(), "maps", kHidden);
	EXPECT_EQ(joined.record.final_estimate.landmarks.size(), 2u);
	EXPECT_EQ(joined.audit.matchedCount(), 1u);
	EXPECT_EQ(joined.audit.wrongCount(), 0u);
	const auto to_file = joined.audit.filterToTrue();
	ASSERT_EQ(to_file.size(), 2u);
	EXPECT_EQ(to_file.at(joined.reports[0].associations[0].id), 1);
	EXPECT_EQ(to_file.at(joined.reports[1].associations[1].id), 2);
}

/// A joiner with a bug: it reports nothing for any map.
class SilentJoiner : public DeadReckoningJoiner
{
   public:
	esif::StepReport mapReport(std::size_t) const override { return {}; }
};

TEST(LocalMapReplay, ReportOfWrongSizeNamesThePlugin)
{
	SilentJoiner joiner;
	try
	{
		esif::replayLocalMaps(joiner, twoMaps(), "maps", kShown);
		FAIL() << "expected std::logic_error";
	}
	catch (const std::logic_error& e)
	{
		const std::string what = e.what();
		EXPECT_NE(what.find("plugin esif::test::DeadReckoningJoiner"), std::string::npos) << what;
		EXPECT_NE(what.find("0 associations for the 1 features of local map 1"), std::string::npos) << what;
	}
}

/// A joiner that runs out of memory joining map `fail_at_map` (0: in finish()).
class StarvedJoiner : public DeadReckoningJoiner
{
   public:
	explicit StarvedJoiner(std::size_t fail_at_map) : fail_at_map_(fail_at_map) {}
	void joinLocalMap(const esif::LocalMap& map) override
	{
		if (map.index == fail_at_map_) throw std::bad_alloc();
		DeadReckoningJoiner::joinLocalMap(map);
	}
	void finish() override
	{
		if (fail_at_map_ == 0) throw std::bad_alloc();
		DeadReckoningJoiner::finish();
	}

   private:
	std::size_t fail_at_map_;
};

std::string numericalErrorOf(DeadReckoningJoiner& joiner)
{
	try
	{
		esif::replayLocalMaps(joiner, twoMaps(), "maps", kShown);
	}
	catch (const esif::NumericalError& e)
	{
		return e.what();
	}
	return "(no NumericalError)";
}

TEST(LocalMapReplay, OutOfMemoryNamesTheMapThePluginAndItsStateSize)
{
	// After map 1 the state holds its end pose and one landmark: 3 + 2.
	StarvedJoiner at_map_2(2);
	EXPECT_EQ(
		numericalErrorOf(at_map_2),
		"maps: out of memory at local map 2 in plugin esif::test::DeadReckoningJoiner (state of dimension 5)");
	// Both maps joined: two end poses, landmarks 1 and 2 (3 x 2 + 2 x 2).
	StarvedJoiner in_finish(0);
	EXPECT_EQ(
		numericalErrorOf(in_finish),
		"maps: out of memory after the last local map in plugin esif::test::DeadReckoningJoiner (state of "
		"dimension 10)");
}

TEST(LocalMapReplay, PluginThatCannotJoinIsRefused)
{
	esif::test::FakePlugin plugin;
	EXPECT_THROW(esif::replayLocalMaps(plugin, twoMaps(), "maps", kShown), std::invalid_argument);
}

}  // namespace
