// A plugin that needs landmark IDs is refused, with the fix in the message,
// when no measurement of the whole log carries one; others always run.

#include <FakePlugin.h>
#include <FakeRawlog.h>

#include <esif/core/Errors.h>
#include <esif/run/LandmarkIdRequirement.h>

#include <gtest/gtest.h>

namespace
{
using esif::test::FakePlugin;
using esif::test::makeRawlog;

std::string errorOf(const esif::FilterPlugin& plugin, const esif::Rawlog& log, const esif::LandmarkIdSource& source)
{
	try
	{
		esif::requireLandmarkIds(plugin, log, source);
	}
	catch (const esif::ConfigError& e)
	{
		return e.what();
	}
	return "";
}

TEST(LandmarkIdRequirement, AnyIdAnywhereIsEnough)
{
	EXPECT_FALSE(esif::hasAnyLandmarkId(makeRawlog({{{std::nullopt}}, std::nullopt})));
	EXPECT_FALSE(esif::hasAnyLandmarkId(makeRawlog({})));
	EXPECT_TRUE(esif::hasAnyLandmarkId(makeRawlog({{{std::nullopt}}, std::nullopt, {{std::nullopt, 3}}})));

	FakePlugin plugin;
	plugin.needs_ids = true;
	EXPECT_NO_THROW(esif::requireLandmarkIds(plugin, makeRawlog({{{std::nullopt}}, {{5}}}), {"c.ini", false, ""}));
}

TEST(LandmarkIdRequirement, LargestInputIdIsTheRecordedAssociationsOrTheRawlogs)
{
	// Plugins number their own landmarks above it (FilterPlugin::reserveLandmarkIds).
	EXPECT_EQ(esif::largestInputLandmarkId(makeRawlog({{{std::nullopt}}, std::nullopt}), nullptr), std::nullopt);
	const auto log = makeRawlog({{{4, std::nullopt}}, {{17, 2}}});
	EXPECT_EQ(esif::largestInputLandmarkId(log, nullptr), 17);
	// A recorded association's IDs replace the rawlog's; its rejected rows carry none.
	esif::RecordedAssociations recorded;
	recorded.steps.resize(2);
	recorded.steps[0].associations = {{esif::Association::Kind::New, 3}, {esif::Association::Kind::Rejected, -1}};
	recorded.steps[1].associations = {{esif::Association::Kind::Matched, 3}, {esif::Association::Kind::New, 9}};
	EXPECT_EQ(esif::largestInputLandmarkId(log, &recorded), 9);
	recorded.steps[1].associations = {{esif::Association::Kind::Rejected, -1}, {esif::Association::Kind::Rejected, -1}};
	recorded.steps[0].associations[0] = {esif::Association::Kind::Rejected, -1};
	EXPECT_EQ(esif::largestInputLandmarkId(log, &recorded), std::nullopt);
}

TEST(LandmarkIdRequirement, PluginThatAssociatesItselfNeedsNoIds)
{
	FakePlugin plugin;
	EXPECT_NO_THROW(esif::requireLandmarkIds(plugin, makeRawlog({{{std::nullopt}}}), {"c.ini", true, ""}));
}

TEST(LandmarkIdRequirement, NoIdsNamesConfigPluginRawlogAndFix)
{
	FakePlugin plugin;
	plugin.needs_ids = true;
	const auto log = makeRawlog({{{std::nullopt, std::nullopt}}, std::nullopt}, "/data/vp.rawlog");
	EXPECT_EQ(
		errorOf(plugin, log, {"cfg/full.ini", false, ""}),
		"cfg/full.ini: plugin test::FakePlugin needs landmark IDs, but the rawlog /data/vp.rawlog has none: set "
		"[esif] associations_from = <a run folder, or in esif compare the label of another config> to use that "
		"run's data association");
	EXPECT_NE(
		errorOf(plugin, log, {"cfg/full.ini", true, ""}).find("has none (hide_landmark_ids = true): set [esif] "
															  "associations_from = "),
		std::string::npos);
}

TEST(LandmarkIdRequirement, AssociationsThatRejectEverythingAreNamed)
{
	FakePlugin plugin;
	plugin.needs_ids = true;
	const auto message =
		errorOf(plugin, makeRawlog({{{std::nullopt}}}), {"full.ini", true, "out/ekf/associations.txt"});
	EXPECT_EQ(
		message,
		"full.ini: plugin test::FakePlugin needs landmark IDs, but the associations out/ekf/associations.txt give "
		"none (every measurement rejected)");
}

}  // namespace
