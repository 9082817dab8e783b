/// \file test_FigureWriter.cpp
/// The figures gnuplot draws for esif, read back pixel by pixel from the PNG
/// (the SVG twin is checked to be an SVG): the information pattern lies on
/// the non-zeros, large patterns do not vanish, the step-time plot is scaled
/// to the bulk of the data, bands are drawn, twelve series get twelve
/// colours, text from a run cannot inject gnuplot commands, failures name
/// the file and leave nothing behind, and `esif run` writes the figures it
/// should.

#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/render/FigureWriter.h>
#include <esif/render/MapOverlay.h>

#include "PlotScript.h"

#include <mrpt/img/CImage.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
using esif::InformationPattern;
using esif::test::TempDir;
using Sparse = Eigen::SparseMatrix<double>;

struct Rgb
{
	int r = 0, g = 0, b = 0;
};

Rgb rgbOf(const std::string& hex)
{
	Rgb c;
	EXPECT_EQ(std::sscanf(hex.c_str(), "#%2x%2x%2x", &c.r, &c.g, &c.b), 3) << hex;
	return c;
}

mrpt::img::CImage load(const std::string& path)
{
	mrpt::img::CImage img;
	EXPECT_TRUE(img.loadFromFile(path)) << path;
	return img;
}

bool is(const mrpt::img::CImage& img, int x, int y, const Rgb& c)
{
	const auto* px = img.ptr<uint8_t>(x, y);  // B, G, R
	return px[2] == c.r && px[1] == c.g && px[0] == c.b;
}

/// Pixels of exactly colour `c` in the columns [x0, x1) and rows [y0, y1).
struct Found
{
	int count = 0;
	int x_min = 1 << 30, x_max = -1, y_min = 1 << 30, y_max = -1;
};

Found find(const mrpt::img::CImage& img, const Rgb& c, int x0 = 0, int x1 = -1, int y0 = 0, int y1 = -1)
{
	if (x1 < 0) x1 = static_cast<int>(img.getWidth());
	if (y1 < 0) y1 = static_cast<int>(img.getHeight());
	Found f;
	for (int y = y0; y < y1; ++y)
		for (int x = x0; x < x1; ++x)
			if (is(img, x, y, c))
			{
				++f.count;
				f.x_min = std::min(f.x_min, x), f.x_max = std::max(f.x_max, x);
				f.y_min = std::min(f.y_min, y), f.y_max = std::max(f.y_max, y);
			}
	return f;
}

const Rgb kBlack{0, 0, 0};

/// An n x n matrix with value 1 wherever keep(i, j).
Sparse pattern(int n, const std::function<bool(int, int)>& keep)
{
	std::vector<Eigen::Triplet<double>> t;
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j)
			if (keep(i, j)) t.emplace_back(i, j, 1.0);
	Sparse m(n, n);
	m.setFromTriplets(t.begin(), t.end());
	return m;
}

bool tridiagonal(int i, int j) { return std::abs(i - j) <= 1; }
bool lowerBidiagonal(int i, int j) { return i == j || i == j + 1; }

/// Checks the centre pixel of each of the n x n cells of the black box
/// found in [x0, x1): black exactly where nonzero(i, j). The box is the
/// matrix when its corner entries are non-zero.
int wrongCells(const mrpt::img::CImage& img, int x0, int x1, int n, const std::function<bool(int, int)>& nonzero)
{
	const Found box = find(img, kBlack, x0, x1);
	EXPECT_GT(box.count, 0);
	const double w = (box.x_max - box.x_min + 1.0) / n, h = (box.y_max - box.y_min + 1.0) / n;
	int wrong = 0;
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j)
		{
			const int x = box.x_min + static_cast<int>((j + 0.5) * w), y = box.y_min + static_cast<int>((i + 0.5) * h);
			wrong += is(img, x, y, kBlack) != nonzero(i, j);
		}
	return wrong;
}

/// Folder entries (names), to check that a failed write left nothing.
std::vector<std::string> entries(const std::string& dir)
{
	std::vector<std::string> names;
	for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
	std::sort(names.begin(), names.end());
	return names;
}

/// gnuplot's SVG: an XML document whose root is <svg> and that is complete.
bool isSvg(const std::string& path)
{
	std::ifstream in(path, std::ios::binary);
	const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
	return text.rfind("<?xml", 0) == 0 && text.find("<svg") != std::string::npos &&
		   text.find("</svg>") != std::string::npos;
}

TEST(FigureWriter, SmallPatternIsBlackExactlyOnItsNonZerosAndHasItsSvg)
{
	TempDir dir;
	InformationPattern p;
	p.information = pattern(10, tridiagonal);
	p.information.coeffRef(2, 7) = 0.0;	 // a stored zero is not a non-zero
	esif::writeInformationPatternImage(p, dir.file("info.png"), 400);
	const auto img = load(dir.file("info.png"));
	EXPECT_EQ(img.getWidth(), 400u);
	EXPECT_EQ(img.getHeight(), 400u);
	EXPECT_EQ(wrongCells(img, 0, 400, 10, tridiagonal), 0);
	EXPECT_TRUE(isSvg(dir.file("info.svg")));
	EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"info.png", "info.svg"}));
}

TEST(FigureWriter, FactorIsDrawnBesideTheInformationMatrix)
{
	TempDir dir;
	InformationPattern p;
	p.information = pattern(10, tridiagonal);
	p.factor = pattern(10, lowerBidiagonal);
	p.factor_order = "natural order";
	esif::writeInformationPatternImage(p, dir.file("info.png"), 300);
	const auto img = load(dir.file("info.png"));
	EXPECT_EQ(img.getWidth(), 600u);
	EXPECT_EQ(img.getHeight(), 300u);
	EXPECT_EQ(wrongCells(img, 0, 300, 10, tridiagonal), 0);
	EXPECT_EQ(wrongCells(img, 300, 600, 10, lowerBidiagonal), 0);
}

TEST(FigureWriter, LargeDiagonalStillShowsAsAnUnbrokenDiagonal)
{
	TempDir dir;
	InformationPattern p;
	p.information.resize(100000, 100000);
	p.information.setIdentity();
	esif::writeInformationPatternImage(p, dir.file("info.png"), 500);
	const auto img = load(dir.file("info.png"));
	// Shown in 500 / 6 = 83 cells a side: every diagonal cell black, every other white.
	EXPECT_EQ(wrongCells(img, 0, 500, 83, [](int i, int j) { return i == j; }), 0);
}

TEST(FigureWriter, SingleNonZeroInAHugeMatrixIsNotLost)
{
	TempDir dir;
	InformationPattern p;
	p.information.resize(100000, 100000);
	p.information.insert(0, 0) = 1.0;  // the corners frame the matrix
	p.information.insert(99999, 99999) = 1.0;
	p.information.insert(12345, 77777) = 1.0;
	esif::writeInformationPatternImage(p, dir.file("info.png"), 400);
	const auto img = load(dir.file("info.png"));
	// 400 / 6 = 66 cells a side.
	const auto cell = [](long long k) { return static_cast<int>(k * 66 / 100000); };
	EXPECT_EQ(wrongCells(img, 0, 400, 66, [&](int i, int j) {
		return (i == 0 && j == 0) || (i == 65 && j == 65) || (i == cell(12345) && j == cell(77777));
	}), 0);
}

TEST(FigureWriter, EmptyMatricesAndNoStepsStillGiveAFigure)
{
	TempDir dir;
	esif::writeInformationPatternImage(InformationPattern{}, dir.file("info.png"), 200);
	EXPECT_EQ(load(dir.file("info.png")).getWidth(), 200u);
	esif::writeStepTimesImage({}, {}, dir.file("steps.png"), 200);
	EXPECT_EQ(load(dir.file("steps.png")).getWidth(), 200u);
	esif::writeLineChartImage({"empty", "x", {esif::LinePanel{"y", {}}}}, dir.file("chart.png"), 300);
	EXPECT_TRUE(isSvg(dir.file("chart.svg")));
}

const Rgb kDotColour = rgbOf("#7f9fd8");  ///< step_times.png's dots

TEST(FigureWriter, StepTimesImageHasTheRequestedWidthAndShowsDotsAndMedians)
{
	// Time grows with the landmarks: the median line climbs to the right.
	std::vector<double> us;
	std::vector<std::size_t> counts;
	for (int k = 0; k < 3000; ++k)
	{
		counts.push_back(static_cast<std::size_t>(k / 10));
		us.push_back(100.0 + 10.0 * (k / 10) + (k % 7) * 20.0);
	}
	TempDir dir;
	esif::writeStepTimesImage(us, counts, dir.file("steps.png"), 640);
	const auto img = load(dir.file("steps.png"));
	ASSERT_EQ(img.getWidth(), 640u);
	ASSERT_EQ(img.getHeight(), 480u);
	EXPECT_GT(find(img, kDotColour).count, 500);
	const Rgb median = rgbOf("#e6194b");
	const Found left = find(img, median, 0, 200), right = find(img, median, 440, 640);
	ASSERT_GT(left.count, 0);
	ASSERT_GT(right.count, 0);
	EXPECT_GT(left.y_min, right.y_max + 100) << "the median line should climb to the right";
}

TEST(FigureWriter, StepTimeOutliersAreClippedSoTheBulkFillsThePlot)
{
	// 5000 steps of 1-2 ms and three of 10 s: the axis ends at the 99.9th
	// percentile, so the bulk spans most of the plot's height.
	std::vector<double> us;
	std::vector<std::size_t> counts;
	for (int k = 0; k < 5000; ++k)
	{
		counts.push_back(static_cast<std::size_t>(k / 50));
		us.push_back(1000.0 + (k % 11) * 100.0);
	}
	for (int k = 0; k < 3; ++k) us.push_back(1e7), counts.push_back(50);
	TempDir dir;
	esif::writeStepTimesImage(us, counts, dir.file("steps.png"), 800);
	const Found dots = find(load(dir.file("steps.png")), kDotColour);
	ASSERT_GT(dots.count, 200);
	EXPECT_GT(dots.y_max - dots.y_min, 600 / 3) << "outliers squash the bulk";
}

TEST(FigureWriter, LocalMapTimesShowBothLinesInBothPanels)
{
	std::vector<esif::LocalMapFusionCost> costs;
	for (int k = 0; k < 60; ++k) costs.push_back({std::size_t(k), 0.001 * (k + 1), 0.0004 * (k + 1), std::size_t(10 + 3 * k)});
	TempDir dir;
	esif::writeLocalMapTimesImage(costs, dir.file("lm.png"), 800);
	const auto img = load(dir.file("lm.png"));
	ASSERT_EQ(img.getWidth(), 800u);
	ASSERT_EQ(img.getHeight(), 600u);
	for (int series = 0; series < 2; ++series)
	{
		const Rgb c = rgbOf(esif::plot::seriesColour(series));
		EXPECT_GT(find(img, c, 0, 800, 0, 300).count, 100) << "series " << series << " in the top panel";
		EXPECT_GT(find(img, c, 0, 800, 300, 600).count, 100) << "series " << series << " in the bottom panel";
	}
	EXPECT_THROW(esif::writeLocalMapTimesImage(costs, dir.file("bad.png"), 100), esif::ConfigError);
	EXPECT_FALSE(fs::exists(dir.file("bad.png")));
}

/// A 40 m square driven once, shifted up by offset_y, with 16 landmarks
/// beside its bottom and top sides.
esif::RunOutputs squareRun(double offset_y)
{
	esif::RunOutputs run;
	for (int k = 0; k <= 160; ++k)
	{
		const double t = k / 40.0;	// side index and position along it
		const int side = std::min(3, static_cast<int>(t));
		const double u = 40.0 * (t - side);
		const double xy[4][2] = {{u, 0}, {40, u}, {40 - u, 40}, {0, 40 - u}};
		run.trajectory.push_back({0.1 * k, {xy[side][0], offset_y + xy[side][1], 0}});
	}
	for (int i = 0; i < 16; ++i)
		run.landmarks.push_back({i, Eigen::Vector2d(2.5 * i + 1, offset_y + (i % 2 ? -3.0 : 43.0)), Eigen::Matrix2d::Identity()});
	return run;
}

TEST(FigureWriter, MapOverlayIsFramedOnTheReferenceWhateverAnotherRunDid)
{
	const esif::RunOutputs ref = squareRun(0);
	esif::RunOutputs close = squareRun(1.0), diverged = ref;
	diverged.landmarks.back().mean = Eigen::Vector2d(2.14e5, 0);
	for (auto& p : diverged.trajectory) p.pose.x -= 1.0;
	TempDir dir;
	esif::writeMapOverlayImage({{"optimum", ref}, {"close", close}, {"diverged", diverged}}, "overlay",
		dir.file("o.png"), 800);
	const auto img = load(dir.file("o.png"));
	ASSERT_EQ(img.getWidth(), 800u);
	ASSERT_EQ(img.getHeight(), 600u);
	const Found reference = find(img, kBlack);
	EXPECT_GT(reference.x_max - reference.x_min, 300) << "the reference fills the frame";
	EXPECT_GT(find(img, rgbOf(esif::plot::seriesColour(0))).count, 300);
	EXPECT_GT(find(img, rgbOf(esif::plot::seriesColour(1))).count, 300);
	EXPECT_TRUE(isSvg(dir.file("o.svg")));
	EXPECT_THROW(esif::writeMapOverlayImage({}, "t", dir.file("none.png"), 800), esif::ConfigError);
	EXPECT_THROW(esif::writeMapOverlayImage({{"r", ref}}, "t", dir.file("small.png"), 100), esif::ConfigError);
	EXPECT_FALSE(fs::exists(dir.file("none.png")));
	EXPECT_FALSE(fs::exists(dir.file("small.png")));
}

TEST(FigureWriter, TwelveRunsOverlaidGetTwelveColours)
{
	std::vector<esif::MapOverlayLayer> layers{{"reference", squareRun(0)}};
	for (int i = 0; i < 12; ++i) layers.push_back({"run " + std::to_string(i), squareRun(0.3 * (i + 1))});
	TempDir dir;
	esif::writeMapOverlayImage(layers, "twelve", dir.file("o.png"), 1200);
	const auto img = load(dir.file("o.png"));
	for (std::size_t i = 0; i < 12; ++i)
		EXPECT_GT(find(img, rgbOf(esif::plot::seriesColour(i))).count, 20) << "run " << i << " is not drawn in its colour";
}

/// CIE76 distance in L*a*b* (D65) between two sRGB colours.
double deltaE(const Rgb& a, const Rgb& b)
{
	const auto lab = [](const Rgb& c) {
		const auto lin = [](int v) {
			const double s = v / 255.0;
			return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
		};
		const double r = lin(c.r), g = lin(c.g), bl = lin(c.b);
		const double x = (0.4124 * r + 0.3576 * g + 0.1805 * bl) / 0.95047, y = 0.2126 * r + 0.7152 * g + 0.0722 * bl,
					 z = (0.0193 * r + 0.1192 * g + 0.9505 * bl) / 1.08883;
		const auto f = [](double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116; };
		return std::array<double, 3>{116 * f(y) - 16, 500 * (f(x) - f(y)), 200 * (f(y) - f(z))};
	};
	const auto p = lab(a), q = lab(b);
	return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
}

TEST(FigureWriter, TheTwelveSeriesColoursAreFarApartAndVisibleOnWhite)
{
	// A CIE76 distance of 20 is a difference anyone sees side by side at a
	// glance (2.3 is a just-noticeable one); 12 is the issue's requirement.
	const auto& colours = esif::plot::seriesColours();
	const Rgb white{255, 255, 255};
	for (std::size_t i = 0; i < colours.size(); ++i)
	{
		EXPECT_GT(deltaE(rgbOf(colours[i]), white), 30) << colours[i] << " is too pale on white";
		for (std::size_t j = i + 1; j < colours.size(); ++j)
			EXPECT_GT(deltaE(rgbOf(colours[i]), rgbOf(colours[j])), 20) << colours[i] << " vs " << colours[j];
	}
}

TEST(FigureWriter, LineChartBreaksALineWhereAPointIsNotFinite)
{
	TempDir dir;
	// One panel, a line at y = 0.5 over x in [0, 100] with a hole from 40 to
	// 60; a second line up to y = 2 keeps the first one low, clear of the legend.
	esif::LineSeries line{"std", {}}, other{"other", {{0, 2}, {100, 2}}};
	for (int x = 0; x <= 100; ++x) line.points.emplace_back(x, x > 40 && x < 60 ? NAN : 0.5);
	esif::writeLineChartImage({"chart", "step", {{"sigma [m]", {line, other}}}}, dir.file("chart.png"), 800);
	const auto img = load(dir.file("chart.png"));
	const Rgb c = rgbOf(esif::plot::seriesColour(0));
	std::vector<int> columns;
	for (int x = 0; x < 800; ++x)
		if (find(img, c, x, x + 1, 150, 600).count > 0) columns.push_back(x);
	ASSERT_FALSE(columns.empty());
	int widest_gap = 0;
	for (std::size_t i = 1; i < columns.size(); ++i) widest_gap = std::max(widest_gap, columns[i] - columns[i - 1]);
	// The hole is 18 of the 100 units the line spans (41 to 59 are missing).
	const double span = columns.back() - columns.front();
	EXPECT_GT(span, 500);
	EXPECT_NEAR(widest_gap / span, 0.18, 0.03);
}

TEST(FigureWriter, BandsAreDrawnUnderTheLinesOnLogAxesToo)
{
	// The pose-ANEES chart of a campaign: a log axis, grey 95% bounds.
	esif::LinePanel panel{"ANEES", {{"ekf", {}}}, {{"95% bounds", {}, -1}}, true};
	for (int k = 0; k <= 100; ++k)
	{
		panel.series[0].points.emplace_back(k, 1.0 + 0.2 * std::sin(k / 5.0));
		panel.bands[0].points.push_back({double(k), 0.6, 1.6});
	}
	TempDir dir;
	esif::writeLineChartImage({"anees", "step", {panel}, "Fig. 3.15"}, dir.file("anees.png"), 800);
	const Found band = find(load(dir.file("anees.png")), rgbOf("#c8c8c8"));
	EXPECT_GT(band.count, 20000) << "the band covers a good part of the plot";
	EXPECT_GT(band.x_max - band.x_min, 500);
}

TEST(FigureWriter, TextFromARunCannotInjectGnuplotCommands)
{
	TempDir dir;
	const std::string evil = dir.file("evil.txt");
	// A quote ends a gnuplot string; a newline ends a command.
	const std::string label = "a' ; set output '" + evil + "'\nset output '" + evil + "' #";
	esif::LineSeries s{label, {{0, 1}, {1, 2}}};
	esif::writeLineChartImage({label, label, {{label, {s}}}}, dir.file("chart.png"), 400);
	EXPECT_FALSE(fs::exists(evil));
	EXPECT_EQ(esif::plot::quoted("it's\n"), "'it''s '");
}

TEST(FigureWriter, InvalidArgumentsAreRefusedBeforeWriting)
{
	TempDir dir;
	EXPECT_THROW(esif::writeStepTimesImage({1.0, 2.0}, {1}, dir.file("a.png"), 640), std::invalid_argument);
	EXPECT_THROW(esif::writeStepTimesImage({1.0}, {1}, dir.file("b.png"), 100), esif::ConfigError);
	EXPECT_THROW(esif::writeInformationPatternImage(InformationPattern{}, dir.file("c.png"), 20000), esif::ConfigError);
	EXPECT_TRUE(entries(dir.path()).empty());
}

template <class Write>
void expectInputErrorNaming(const std::string& path, Write write)
{
	try
	{
		write();
		FAIL() << "expected InputError";
	}
	catch (const esif::InputError& e)
	{
		EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
	}
}

TEST(FigureWriter, UnwritablePathThrowsInputErrorNamingItAndLeavesNothing)
{
	TempDir dir;
	InformationPattern p;
	p.information = pattern(4, tridiagonal);
	const std::string missing = dir.file("no/such/folder/info.png");
	expectInputErrorNaming(missing, [&] { esif::writeInformationPatternImage(p, missing, 300); });
	const std::string steps = dir.file("no/such/folder/steps.png");
	expectInputErrorNaming(steps, [&] { esif::writeStepTimesImage({1.0}, {1}, steps, 300); });
	EXPECT_TRUE(entries(dir.path()).empty());

	// A folder in the way of the PNG: gnuplot draws both, the PNG's rename
	// fails, and neither the SVG nor a temporary file is left.
	fs::create_directory(dir.file("taken.png"));
	EXPECT_THROW(esif::writeInformationPatternImage(p, dir.file("taken.png"), 300), esif::InputError);
	EXPECT_THROW(esif::writeStepTimesImage({1.0}, {1}, dir.file("taken.png"), 300), esif::InputError);
	EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"taken.png"});
}

TEST(FigureWriter, MissingGnuplotIsOneErrorNamingTheFigureAndWhatToInstall)
{
	TempDir dir;
	const std::string path = dir.file("steps.png");
	const std::string saved = std::getenv("PATH") ? std::getenv("PATH") : "";
	::setenv("PATH", dir.path().c_str(), 1);
	try
	{
		esif::writeStepTimesImage({1.0}, {1}, path, 300);
		ADD_FAILURE() << "expected InputError";
	}
	catch (const esif::InputError& e)
	{
		const std::string what = e.what();
		EXPECT_NE(what.find(path), std::string::npos) << what;
		EXPECT_NE(what.find("gnuplot-nox"), std::string::npos) << what;
	}
	::setenv("PATH", saved.c_str(), 1);
	EXPECT_TRUE(entries(dir.path()).empty());
}

TEST(FigureWriter, EsifRunWritesStepTimesButNoInfoMatrixForTheEkf)
{
	TempDir dir;
	const std::string rawlog = dir.file("small.rawlog");
	const auto sim = esif::test::simulateSmall(rawlog);
	ASSERT_EQ(sim.exit_code, 0) << sim.out;
	const std::string out = dir.file("out");
	const auto run = esif::test::runEsif(
		"run -q --config '" + esif::test::sourcePath("configs/ekf.ini") + "' --rawlog '" + rawlog + "' --out '" +
		out + "'");
	ASSERT_EQ(run.exit_code, 0) << run.out;

	const auto img = load(out + "/step_times.png");
	EXPECT_EQ(img.getWidth(), 1000u);  // [esif] image_size_px's default
	EXPECT_TRUE(isSvg(out + "/step_times.svg"));
	EXPECT_TRUE(isSvg(out + "/map.svg"));
	EXPECT_FALSE(fs::exists(out + "/info_matrix.png")) << "the EKF has no information pattern";
	for (const auto& name : entries(out)) EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
}

}  // namespace

namespace
{
TEST(FigureWriter, EsifRunWithNoFiguresWritesTheDataFilesOnly)
{
	TempDir dir;
	const std::string rawlog = dir.file("small.rawlog");
	ASSERT_EQ(esif::test::simulateSmall(rawlog).exit_code, 0);
	const std::string out = dir.file("out");
	const std::string config = esif::test::sourcePath("configs/dslam.ini");
	const auto run =
		esif::test::runEsif("run -q --no-figures --config '" + config + "' --rawlog '" + rawlog + "' --out '" + out + "'");
	ASSERT_EQ(run.exit_code, 0) << run.out;
	for (const auto& name : entries(out))
	{
		const std::string ext = fs::path(name).extension().string();
		EXPECT_TRUE(ext != ".png" && ext != ".svg") << name << " drawn despite --no-figures";
	}
	for (const char* data : {"stats.json", "landmarks.txt", "trajectory.tum", "map.simplemap", "landmarks.gz"})
		EXPECT_TRUE(fs::is_regular_file(out + "/" + data)) << data;

	// Local-map runs have no such option: one error, nothing written.
	const auto refused = esif::test::runEsif("run -q --no-figures --config '" + config + "' --local-maps '" +
											 dir.path() + "' --out '" + dir.file("lm") + "'");
	EXPECT_NE(refused.exit_code, 0);
	EXPECT_NE(refused.out.find("--no-figures applies to --rawlog input"), std::string::npos) << refused.out;
	EXPECT_FALSE(fs::exists(dir.file("lm")));
}
}  // namespace
