// comparison.html and summary.html as a browser shows them: a real
// `esif compare` (EKF and D-SLAM on rawlogs/grid196.rawlog, measured
// against the EKF so the maps overlay is drawn) and a real `esif
// montecarlo` (2 runs of configs/sim/small.ini), each page then loaded in
// headless Chromium: the table is there, every <img> decoded (naturalWidth
// > 0, checked on a copy with a checking script appended; the page itself
// has none) and a screenshot of the page is not blank. Skipped when
// Chromium is not installed. About 10 s.

#include <EsifTestSupport.h>

#include <mrpt/img/CImage.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>

namespace
{
namespace fs = std::filesystem;
using esif::test::quoted;
using esif::test::readText;
using esif::test::runEsif;
using esif::test::sourcePath;
using esif::test::TempDir;

/// The browser: chromium or chromium-browser on PATH, else "".
std::string chromium()
{
	for (const char* name : {"chromium", "chromium-browser"})
	{
		const auto found = esif::test::runShell("command -v " + std::string(name));
		if (found.exit_code == 0 && !found.out.empty())
			return found.out.substr(0, found.out.find_first_of("\r\n"));
	}
	return "";
}

/// Headless Chromium on `page` with `args` (its own profile folder under
/// `tmp`; --no-sandbox since CI runs as root); returns its stdout.
std::string runChromium(const std::string& browser, const TempDir& tmp, const std::string& args, const std::string& page)
{
	const std::string cmd = "timeout 60 " + quoted(browser) +
							" --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --hide-scrollbars --no-first-run "
							"--user-data-dir=" +
							quoted(tmp.file("chromium-profile")) + " " + args + " " + quoted("file://" + page) +
							" 2>/dev/null";
	// In a subshell: its stderr (Chromium's chatter) stays out of the output.
	return esif::test::runShell("(" + cmd + ")").out;
}

/// A copy of `page` with a script appended that, once everything loaded,
/// writes "ESIF-CHECK tables=T images=I decoded=D" into the document.
std::string checkingCopy(const std::string& page, const std::string& copy)
{
	std::string html = readText(page);
	const auto end = html.rfind("</body>");
	if (end == std::string::npos) return "";
	html.insert(
		end,
		"<script>window.addEventListener('load', function () {"
		" var decoded = 0; for (const i of document.images) if (i.complete && i.naturalWidth > 0) ++decoded;"
		" var p = document.createElement('pre'); p.id = 'esif-check';"
		" p.textContent = 'ESIF-CHECK tables=' + document.querySelectorAll('table tbody tr').length"
		" + ' images=' + document.images.length + ' decoded=' + decoded;"
		" document.body.appendChild(p); });</script>\n");
	std::ofstream(copy) << html;
	return copy;
}

std::size_t count(const std::string& text, const std::string& what)
{
	std::size_t n = 0;
	for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
	return n;
}

/// Loads `page` in the browser: its table rows are there and every image decoded; a screenshot is not blank.
void expectRendered(const std::string& browser, const TempDir& tmp, const std::string& page, std::size_t min_images)
{
	const std::string source = readText(page);
	const std::size_t images = count(source, "<img ");
	EXPECT_GE(images, min_images) << page;
	const std::string copy = checkingCopy(page, tmp.file("check_" + fs::path(page).filename().string()));
	ASSERT_FALSE(copy.empty()) << page << ": no </body>";
	const std::string dom = runChromium(browser, tmp, "--dump-dom --virtual-time-budget=10000", copy);
	std::smatch m;
	ASSERT_TRUE(std::regex_search(dom, m, std::regex("ESIF-CHECK tables=(\\d+) images=(\\d+) decoded=(\\d+)")))
		<< "no check result in Chromium's DOM dump of " << copy << ":\n"
		<< dom.substr(0, 2000);
	EXPECT_GT(std::stoul(m[1]), 0u) << "no table row rendered";
	EXPECT_EQ(std::stoul(m[2]), images) << "images in the DOM";
	EXPECT_EQ(std::stoul(m[3]), images) << "images that decoded (naturalWidth > 0)";

	const std::string shot = tmp.file(fs::path(page).stem().string() + "_screenshot.png");
	runChromium(browser, tmp, "--window-size=1280,1600 --screenshot=" + quoted(shot), page);
	mrpt::img::CImage img;
	ASSERT_TRUE(img.loadFromFile(shot)) << "no screenshot " << shot;
	const mrpt::img::CImage gray(img, mrpt::img::FAST_REF_OR_CONVERT_TO_GRAY);
	std::set<int> levels;
	std::size_t dark = 0, pixels = 0;
	for (unsigned y = 0; y < gray.getHeight(); y += 4)
		for (unsigned x = 0; x < gray.getWidth(); x += 4, ++pixels)
		{
			const int v = gray.at<uint8_t>(x, y);
			levels.insert(v);
			dark += v < 128;
		}
	EXPECT_GT(levels.size(), 8u) << shot << ": a blank or flat screenshot";
	EXPECT_GT(dark, pixels / 200) << shot << ": next to nothing drawn";
}

TEST(HtmlPages, ComparisonAndSummaryRenderInChromium)
{
	const std::string browser = chromium();
	if (browser.empty()) GTEST_SKIP() << "chromium is not installed (apt-get install chromium): pages not rendered";
	TempDir tmp;

	const std::string cmp = tmp.file("cmp");
	const auto compared = runEsif(
		"compare --configs " + quoted(sourcePath("configs/ekf.ini") + "," + sourcePath("configs/dslam.ini")) +
		" --rawlog " + quoted(sourcePath("rawlogs/grid196.rawlog")) + " --reference ekf --out " + quoted(cmp));
	ASSERT_EQ(compared.exit_code, 0) << compared.out;
	ASSERT_TRUE(fs::is_regular_file(cmp + "/comparison.html"));
	EXPECT_NE(readText(cmp + "/.esif-output").find("comparison.html"), std::string::npos)
		<< "comparison.html is not listed as esif's own output";
	const std::string page = readText(cmp + "/comparison.html");
	EXPECT_NE(page.find("Table 5.1 layout"), std::string::npos);
	EXPECT_EQ(page.find("not shown"), std::string::npos) << "a figure was left out";
	// The overlay, then each run's map and step times, and D-SLAM's information matrix.
	expectRendered(browser, tmp, cmp + "/comparison.html", 6);

	const std::string mc = tmp.file("mc");
	const auto campaign = runEsif(
		"montecarlo --scenario " + quoted(sourcePath("configs/sim/small.ini")) + " --configs " +
		quoted(sourcePath("configs/ekf.ini")) + " --runs 2 --jobs 2 --out " + quoted(mc));
	ASSERT_EQ(campaign.exit_code, 0) << campaign.out;
	ASSERT_TRUE(fs::is_regular_file(mc + "/summary.html"));
	EXPECT_EQ(readText(mc + "/summary.html").find("not shown"), std::string::npos) << "a figure was left out";
	expectRendered(browser, tmp, mc + "/summary.html", 3);
}

}  // namespace
