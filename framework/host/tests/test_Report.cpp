// The one-page HTML reports (esif/report): escaping, base64, tables,
// inlined figures with their bounds, the structure of comparison.html and
// summary.html, and the column explanations both Markdown and HTML use
// (ColumnMeanings.h) against docs/outputs.md.

#include <EsifTestSupport.h>

#include <esif/compare/BaselineComparison.h>
#include <esif/eval/ColumnMeanings.h>
#include <esif/compare/ComparisonTable.h>
#include <esif/montecarlo/MonteCarloTables.h>
#include <esif/eval/ReferenceResultDifference.h>
#include <esif/eval/RunDifference.h>
#include <esif/compare/ComparisonPage.h>
#include <esif/report/Html.h>
#include <esif/montecarlo/MonteCarloPage.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

namespace
{
namespace fs = std::filesystem;
namespace html = esif::html;

/// A 1 x 1 RGBA PNG and its base64 text.
const unsigned char kPng[] = {
	0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
	0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1f, 0x15, 0xc4, 0x89, 0x00, 0x00, 0x00,
	0x0d, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0x64, 0x60, 0xf8, 0x5f, 0x0f, 0x00, 0x02, 0x87, 0x01, 0x80,
	0xeb, 0x47, 0xba, 0x92, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
const char* const kPngBase64 =
	"iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNkYPhfDwAChwGA60e6kgAAAABJRU5ErkJggg==";

void writeBytes(const std::string& path, const std::string& bytes)
{
	std::ofstream(path, std::ios::binary) << bytes;
}

std::string pngBytes() { return std::string(reinterpret_cast<const char*>(kPng), sizeof(kPng)); }

std::size_t count(const std::string& text, const std::string& what)
{
	std::size_t n = 0;
	for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
	return n;
}

/// Self-contained and script-free: no external resource, no script, no event handler.
void expectSelfContained(const std::string& page)
{
	EXPECT_EQ(page.rfind("<!DOCTYPE html>\n", 0), 0u);
	EXPECT_NE(page.find("<meta charset=\"utf-8\">"), std::string::npos);
	for (const char* banned : {"<script", "<link", "<iframe", "<object", "<embed", "http://", "https://", "src=\"file:"})
		EXPECT_EQ(page.find(banned), std::string::npos) << banned;
	EXPECT_FALSE(std::regex_search(page, std::regex("<[^>]*\\son[a-z]+\\s*=", std::regex::icase))) << "an event handler";
	EXPECT_EQ(count(page, "<table>"), count(page, "</table>"));
	EXPECT_EQ(count(page, "<figure>"), count(page, "</figure>"));
	EXPECT_NE(page.rfind("</html>\n"), std::string::npos);
}

TEST(Html, EscapesEveryMarkupCharacter)
{
	EXPECT_EQ(html::escape("<script>alert(\"x\" & 'y')</script>"),
			  "&lt;script&gt;alert(&quot;x&quot; &amp; &#39;y&#39;)&lt;/script&gt;");
	EXPECT_EQ(html::escape("plain µs text"), "plain µs text");
	EXPECT_EQ(html::escape(""), "");
	EXPECT_EQ(html::withCode("a `b<` and `c`, 1 = `"), "a <code>b&lt;</code> and <code>c</code>, 1 = `");
	EXPECT_EQ(html::withCode("`<script>`"), "<code>&lt;script&gt;</code>");
}

TEST(Html, Base64MatchesRfc4648)
{
	EXPECT_EQ(html::base64(""), "");
	EXPECT_EQ(html::base64("f"), "Zg==");
	EXPECT_EQ(html::base64("fo"), "Zm8=");
	EXPECT_EQ(html::base64("foo"), "Zm9v");
	EXPECT_EQ(html::base64("foobar"), "Zm9vYmFy");
	EXPECT_EQ(html::base64(std::string("\xff\x00\x80", 3)), "/wCA");
	EXPECT_EQ(html::base64(pngBytes()), kPngBase64);
}

TEST(Html, TableEscapesCellsAndTitles)
{
	html::Table t;
	t.header = {{"key", "", true}, {"<run>", "folder \"a\" & 'b'", true}};
	t.rows = {{{"wall_s", "replay <time>", true}, {"1.5", "", false}}, {{"plugin", "", true}, {"<b>Ekf</b>", "", false}}};
	const std::string out = html::table(t);
	EXPECT_NE(out.find("<th title=\"folder &quot;a&quot; &amp; &#39;b&#39;\">&lt;run&gt;</th>"), std::string::npos) << out;
	EXPECT_NE(out.find("<th title=\"replay &lt;time&gt;\">wall_s</th>"), std::string::npos) << out;
	EXPECT_NE(out.find("<td class=\"num\">1.5</td>"), std::string::npos) << out;
	EXPECT_NE(out.find("<td>&lt;b&gt;Ekf&lt;/b&gt;</td>"), std::string::npos) << out;
	EXPECT_EQ(out.find("<b>"), std::string::npos);
}

TEST(Html, InlinesAPngAndNotesWhatItCannotInline)
{
	esif::test::TempDir tmp;
	writeBytes(tmp.file("ok.png"), pngBytes());
	const std::string ok = html::pngFigure(tmp.file("ok.png"), "a <caption>");
	EXPECT_NE(ok.find(std::string("<img src=\"data:image/png;base64,") + kPngBase64 + "\""), std::string::npos) << ok;
	EXPECT_NE(ok.find("width=\"1\" height=\"1\""), std::string::npos) << ok;
	EXPECT_NE(ok.find("<figcaption>a &lt;caption&gt;</figcaption>"), std::string::npos) << ok;

	const auto expectNote = [](const std::string& out, const std::string& why) {
		EXPECT_EQ(out.find("<img"), std::string::npos) << out;
		EXPECT_NE(out.find("<p class=\"note\">"), std::string::npos) << out;
		EXPECT_NE(out.find(why), std::string::npos) << out;
	};
	expectNote(html::pngFigure(tmp.file("absent.png"), "absent"), "absent.png not shown (missing)");
	expectNote(html::pngFigure(tmp.file("ok.png"), "big", 32), "70 bytes (limit 32)");
	writeBytes(tmp.file("text.png"), "<svg onload=alert(1)>not a png at all</svg>");
	expectNote(html::pngFigure(tmp.file("text.png"), "text"), "not a PNG file");
	std::string huge = pngBytes();
	huge[16] = 0x7f;  // width 0x7f000001
	writeBytes(tmp.file("huge.png"), huge);
	expectNote(html::pngFigure(tmp.file("huge.png"), "huge"), "pixels (limit 16384 each way)");
	fs::create_directory(tmp.file("dir.png"));
	expectNote(html::pngFigure(tmp.file("dir.png"), "dir"), "not a regular file");
	// A file name with markup is escaped in the note.
	expectNote(html::pngFigure(tmp.file("<i>.png"), "x"), "&lt;i&gt;.png not shown");
}

TEST(Html, PageIsSelfContained)
{
	const std::string out = html::page("a <title> & more", html::paragraph("body"));
	expectSelfContained(out);
	EXPECT_NE(out.find("<title>a &lt;title&gt; &amp; more</title>"), std::string::npos);
	EXPECT_NE(out.find("<h1>a &lt;title&gt; &amp; more</h1>"), std::string::npos);
}

esif::Stats run(const std::string& label, const std::string& plugin, const std::string& formulation)
{
	esif::Stats s;
	s.set("label", esif::StatValue(label));
	s.set("plugin", esif::StatValue(plugin));
	s.set("formulation", esif::StatValue(formulation));
	s.set("steps", esif::StatValue(200.0));
	s.set("landmarks", esif::StatValue(16.0));
	s.set("state_dim", esif::StatValue(35.0));
	s.set("poses_in_state", esif::StatValue(1.0));
	s.set("wall_s", esif::StatValue(0.25));
	return s;
}

TEST(ComparisonPage, HasTheTableExplainedTheBookTableAndEveryRunsFigures)
{
	esif::test::TempDir tmp;
	const std::string ekf_dir = tmp.file("ekf"), evil_dir = tmp.file("evil"), failed_dir = tmp.file("failed");
	fs::create_directories(ekf_dir);
	fs::create_directories(evil_dir);
	writeBytes(ekf_dir + "/map.png", pngBytes());
	writeBytes(ekf_dir + "/step_times.png", pngBytes());
	writeBytes(tmp.file("maps_overlay.png"), pngBytes());
	std::vector<esif::Stats> runs = {run("ekf", "Ekf", "ekf_slam"), run("<img src=x onerror=alert(1)>", "Dslam", "dslam"),
									 esif::failedRunStats("broken", "Failing", 3, "esif: <boom>")};
	esif::markSucceededRuns(runs);
	const std::string page = esif::comparisonPageHtml(
		{"esif compare on <a>.rawlog", runs, {ekf_dir, evil_dir, failed_dir}, "note one <x>\nnote two\n", tmp.path()});
	expectSelfContained(page);
	EXPECT_EQ(count(page, "<table>"), 2u);	// the comparison and Table 5.1
	EXPECT_EQ(page.find("<img src=x"), std::string::npos);
	EXPECT_NE(page.find("&lt;img src=x onerror=alert(1)&gt;"), std::string::npos);
	EXPECT_EQ(page.find("<boom>"), std::string::npos);
	EXPECT_NE(page.find("<title>esif compare on &lt;a&gt;.rawlog</title>"), std::string::npos);
	// Every row of the table has its explanation on hover and in the legend.
	const auto grid = esif::comparisonGrid(runs);
	for (const auto& key : grid.keys)
	{
		const auto* m = esif::meaningOf(esif::comparisonColumnMeanings(), key);
		ASSERT_NE(m, nullptr) << key;
		EXPECT_NE(page.find("<th title=\"" + html::escape(esif::plainMeaning(*m)) + "\">" + key + "</th>"),
				  std::string::npos)
			<< key;
		EXPECT_NE(page.find("<dt><code>" + html::escape(esif::columnList(*m)) + "</code></dt>"), std::string::npos)
			<< key;
	}
	EXPECT_NE(page.find("<p>note one &lt;x&gt;</p>\n<p>note two</p>"), std::string::npos);
	EXPECT_NE(page.find("Table 5.1 layout"), std::string::npos);
	EXPECT_NE(page.find("<th>Number of non-zeros</th>"), std::string::npos);
	// Figures: the overlay, ekf's map and step times; the evil run's map is missing; the failed run has none.
	EXPECT_EQ(count(page, "<img src=\"data:image/png;base64,"), 3u);
	EXPECT_NE(page.find("map.png not shown (missing)"), std::string::npos);
	EXPECT_NE(page.find("no figures: the run failed"), std::string::npos);
	EXPECT_EQ(page.find(tmp.path()), std::string::npos) << "the page names run folders, not where they were staged";
}

TEST(MonteCarloPage, HasTheSummaryExplainedAndTheFigures)
{
	esif::test::TempDir tmp;
	writeBytes(tmp.file("anees_pose.png"), pngBytes());
	writeBytes(tmp.file("rmse.png"), pngBytes());
	esif::ConfigStatistics c;
	c.name = "<ekf>";
	c.runs = 3;
	c.pose_anees_mean = 3.1;
	esif::CampaignGaps gaps;
	gaps.failed = {"<ekf>/seed_0002: failed (exit 3): esif: <x>"};
	const std::string page = esif::monteCarloPageHtml("esif montecarlo: small", {c}, gaps, tmp.path());
	expectSelfContained(page);
	EXPECT_EQ(count(page, "<table>"), 1u);
	EXPECT_NE(page.find("<th>&lt;ekf&gt;</th>"), std::string::npos) << page;
	EXPECT_EQ(page.find("<ekf>"), std::string::npos);
	for (const auto& m : esif::monteCarloSummaryColumns())
		for (const auto& column : m.columns)
			EXPECT_NE(page.find("<th title=\"" + html::escape(esif::plainMeaning(m)) + "\">" + html::escape(column)),
					  std::string::npos)
				<< column;
	EXPECT_NE(page.find("Runs not aggregated"), std::string::npos);
	EXPECT_EQ(count(page, "<img src=\"data:image/png;base64,"), 2u);
	EXPECT_NE(page.find("landmark_anees.png not shown (missing)"), std::string::npos);
}

/// Every key comparison.md can show is explained.
TEST(ColumnMeanings, CoverEveryRowComparisonMdCanShow)
{
	std::vector<std::string> keys = esif::comparisonKeys();
	for (const auto* more : {&esif::baselineRatioKeys(), &esif::runDifferenceKeys(), &esif::referenceResultKeys()})
		keys.insert(keys.end(), more->begin(), more->end());
	for (const char* k : {"status", "exit_code", "state_nees", "state_nees_dof", "state_nees_consistent", "local_maps",
						  "join_us_mean", "join_us_max"})
		keys.push_back(k);
	for (const auto& k : keys) EXPECT_NE(esif::meaningOf(esif::comparisonColumnMeanings(), k), nullptr) << k;
}

/// summary.md explains its columns from the same list.
TEST(ColumnMeanings, SummaryMdUsesThem)
{
	const std::string md = esif::monteCarloSummaryMarkdown("t", {}, {});
	for (const auto& m : esif::monteCarloSummaryColumns())
		EXPECT_NE(md.find("- " + esif::columnList(m) + ": " + m.meaning + "\n"), std::string::npos) << md;
}

/// docs/outputs.md's tables say the same, word for word.
TEST(ColumnMeanings, AreTheTablesOfDocsOutputsMd)
{
	const std::string docs = esif::test::readText(esif::test::sourcePath("docs/outputs.md"));
	ASSERT_FALSE(docs.empty());
	for (const auto& m : esif::comparisonColumnMeanings())
	{
		std::string keys;
		for (const auto& c : m.columns) keys += (keys.empty() ? "`" : ", `") + c + "`";
		const std::string line = "| " + keys + " | " + (m.when.empty() ? "" : m.when + " | ") + m.meaning + " |\n";
		EXPECT_NE(docs.find(line), std::string::npos) << "docs/outputs.md lacks:\n" << line;
	}
	for (const auto& m : esif::monteCarloSummaryColumns())
	{
		const std::string line = "| " + esif::columnList(m) + " | " + m.meaning + " |\n";
		EXPECT_NE(docs.find(line), std::string::npos) << "docs/outputs.md lacks:\n" << line;
	}
}

}  // namespace
