// esif compare's run order: a config naming another's label in
// associations_from runs after it; everything else keeps its order; a
// self-reference, an ambiguous label or a cycle is one ConfigError.

#include <esif/core/Errors.h>
#include <esif/compare/RunOrder.h>

#include <gtest/gtest.h>

namespace
{
using esif::PlannedRun;

std::vector<std::size_t> orderOf(const std::vector<PlannedRun>& runs)
{
	return esif::runOrder(runs, esif::associationSources(runs));
}

std::string errorOf(const std::vector<PlannedRun>& runs)
{
	try
	{
		orderOf(runs);
	}
	catch (const esif::ConfigError& e)
	{
		return e.what();
	}
	return "";
}

TEST(RunOrder, WithoutReferencesTheGivenOrder)
{
	EXPECT_EQ(orderOf({{"a.ini", "a", ""}, {"b.ini", "b", ""}, {"c.ini", "c", ""}}), (std::vector<std::size_t>{0, 1, 2}));
	EXPECT_TRUE(orderOf({}).empty());
}

TEST(RunOrder, SourceRunsJustBeforeItsFirstUser)
{
	const std::vector<PlannedRun> runs = {{"full.ini", "full", "ekf"}, {"d.ini", "d", ""}, {"ekf.ini", "ekf", ""}};
	const auto sources = esif::associationSources(runs);
	EXPECT_EQ(sources[0].value_or(99), 2u);
	EXPECT_FALSE(sources[1]);
	EXPECT_FALSE(sources[2]);
	EXPECT_EQ(esif::runOrder(runs, sources), (std::vector<std::size_t>{2, 0, 1}));
	// A chain: a <- b <- c, given backwards.
	EXPECT_EQ(orderOf({{"c.ini", "c", "b"}, {"b.ini", "b", "a"}, {"a.ini", "a", ""}}),
			  (std::vector<std::size_t>{2, 1, 0}));
	// Already in order: unchanged.
	EXPECT_EQ(orderOf({{"ekf.ini", "ekf", ""}, {"full.ini", "full", "ekf"}}), (std::vector<std::size_t>{0, 1}));
}

TEST(RunOrder, TheReferenceRunsFirstAfterItsOwnSources)
{
	// compare --reference full: the other runs are measured against it while
	// they run, so it goes first, after the EKF whose association it reuses.
	const std::vector<PlannedRun> runs = {
		{"d.ini", "d", ""}, {"full.ini", "full", "ekf"}, {"s.ini", "s", ""}, {"ekf.ini", "ekf", ""}};
	const auto sources = esif::associationSources(runs);
	EXPECT_EQ(esif::runOrder(runs, sources, 1), (std::vector<std::size_t>{3, 1, 0, 2}));
	EXPECT_EQ(esif::runOrder(runs, sources, 2), (std::vector<std::size_t>{2, 0, 3, 1}));
	EXPECT_EQ(esif::runOrder(runs, sources, std::nullopt), (std::vector<std::size_t>{0, 3, 1, 2}));
}

TEST(RunOrder, AFolderIsNoReference)
{
	const std::vector<PlannedRun> runs = {{"full.ini", "full", "out/ekf"}, {"ekf.ini", "ekf", ""}};
	EXPECT_FALSE(esif::associationSources(runs)[0]);
	EXPECT_EQ(orderOf(runs), (std::vector<std::size_t>{0, 1}));
}

TEST(RunOrder, SelfReferenceIsAnError)
{
	EXPECT_EQ(errorOf({{"a.ini", "a", ""}, {"full.ini", "full", "full"}}),
			  "full.ini: [esif] associations_from = full: names this config's own label (a run cannot reuse its "
			  "own data association)");
	// Another config of the same label is meant, not itself.
	EXPECT_EQ(orderOf({{"full.ini", "x", "x"}, {"ekf.ini", "x", ""}}), (std::vector<std::size_t>{1, 0}));
}

TEST(RunOrder, AmbiguousLabelIsAnError)
{
	EXPECT_EQ(errorOf({{"full.ini", "full", "ekf"}, {"e1.ini", "ekf", ""}, {"e2.ini", "ekf", ""}}),
			  "full.ini: [esif] associations_from = ekf: several compared configs have this label (e1.ini, "
			  "e2.ini); give each its own [esif] label");
}

TEST(RunOrder, CycleIsAnError)
{
	EXPECT_EQ(errorOf({{"x.ini", "x", ""}, {"a.ini", "a", "b"}, {"b.ini", "b", "a"}}),
			  "esif compare: [esif] associations_from forms a cycle: a.ini (a) -> b.ini (b) -> a.ini: no run of it "
			  "can go first");
	EXPECT_NE(errorOf({{"a.ini", "a", "c"}, {"b.ini", "b", "a"}, {"c.ini", "c", "b"}}).find("forms a cycle"),
			  std::string::npos);
}

}  // namespace
