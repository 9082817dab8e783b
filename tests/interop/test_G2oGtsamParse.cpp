// GTSAM's readG2o reads a g2o file with one loop: `is >> tag`, the
// parsers, then `is.ignore(LINESIZE, '\n')`; it stops at the first failed
// read. In the GTSAM versions whose bearing-range parser reads its two
// vertex ids before checking the tag, a line without two numbers after its
// first word (a comment, "FIX 0") fails that read and ends the file there:
// every factor after it is silently dropped and the optimiser "converges"
// on the initial values. Newer versions check the tag first and skip such
// lines. Both rules are replayed here on esif's exported files, for both
// landmark-edge forms: every edge line must be reached.

#include <EsifTestSupport.h>

#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <sstream>
#include <string>

namespace
{
using namespace esif;
using test::quoted;
using test::readText;
using test::runEsif;
using test::TempDir;

enum class GtsamRule
{
	IdsBeforeTag,  ///< the bearing-range parser reads "id1 id2" for every line
	TagFirst	   ///< unknown tags are skipped without a read
};

/// The edge lines (EDGE_SE2, BR, EDGE_SE2_XY) GTSAM's loop reaches, by tag.
std::map<std::string, int> edgesReached(const std::string& text, GtsamRule rule)
{
	std::map<std::string, int> reached;
	std::istringstream is(text);
	std::string tag;
	while (is >> tag)
	{
		const bool known = tag == "VERTEX_SE2" || tag == "VERTEX_XY" || tag == "EDGE_SE2" || tag == "BR" ||
						   tag == "EDGE_SE2_XY";
		if (rule == GtsamRule::IdsBeforeTag || known)
		{
			std::size_t id1 = 0, id2 = 0;
			if (!(is >> id1 >> id2)) break;	 // the fail bit ends GTSAM's loop
		}
		if (tag == "EDGE_SE2" || tag == "BR" || tag == "EDGE_SE2_XY") ++reached[tag];
		is.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
	}
	return reached;
}

/// The edge lines of the file, by tag, as a line scan counts them.
std::map<std::string, int> edgesInFile(const std::string& text)
{
	std::map<std::string, int> count;
	std::istringstream in(text);
	for (std::string line; std::getline(in, line);)
	{
		std::istringstream words(line);
		std::string tag;
		if ((words >> tag) && (tag == "EDGE_SE2" || tag == "BR" || tag == "EDGE_SE2_XY")) ++count[tag];
	}
	return count;
}

TEST(G2oGtsamParse, TheRuleStopsAtACommentOrAFixLineBeforeTheEdges)
{
	// The replay of GTSAM's loop is faithful: the framing esif wrote before
	// loses every edge under the ids-before-tag rule, not under the other.
	const std::string edges = "EDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\nBR 1 5 0.1 2.0 0.01 0.1\n";
	EXPECT_TRUE(edgesReached("# header\n" + edges, GtsamRule::IdsBeforeTag).empty());
	EXPECT_TRUE(edgesReached("VERTEX_SE2 0 0 0 0\nFIX 0\n" + edges, GtsamRule::IdsBeforeTag).empty());
	EXPECT_EQ(edgesReached("# header\nFIX 0\n" + edges, GtsamRule::TagFirst), edgesInFile(edges));
	EXPECT_EQ(edgesReached(edges + "FIX 0\n# trailer\n", GtsamRule::IdsBeforeTag), edgesInFile(edges));
}

class G2oGtsamParseOfExport : public ::testing::TestWithParam<const char*>
{
};

TEST_P(G2oGtsamParseOfExport, EveryEdgeLineIsReachedUnderBothRules)
{
	TempDir dir;
	const std::string g2o = dir.file("grid196.g2o");
	const auto r = runEsif("export g2o --landmark-edge " + std::string(GetParam()) + " --rawlog " +
						   quoted(test::sourcePath("rawlogs/grid196.rawlog")) + " --out " + quoted(g2o));
	ASSERT_EQ(r.exit_code, 0) << r.out;
	const std::string text = readText(g2o);
	const auto in_file = edgesInFile(text);
	ASSERT_EQ(in_file.at("EDGE_SE2"), 3000);
	ASSERT_EQ(in_file.at(GetParam() == std::string("br") ? "BR" : "EDGE_SE2_XY"), 14032);
	EXPECT_EQ(edgesReached(text, GtsamRule::IdsBeforeTag), in_file);
	EXPECT_EQ(edgesReached(text, GtsamRule::TagFirst), in_file);
	// The description and the gauge are still in the file, after the edges.
	EXPECT_NE(text.find("\nFIX 0\n"), std::string::npos);
	EXPECT_NE(text.find("\n# esif export g2o: the full-SLAM problem of "), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(BothLandmarkEdges, G2oGtsamParseOfExport, ::testing::Values("br", "xy"));

}  // namespace
