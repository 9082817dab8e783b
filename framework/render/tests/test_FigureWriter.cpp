/// \file test_FigureWriter.cpp
/// info_matrix.png and step_times.png are read back pixel by pixel: the
/// pattern lies exactly on the non-zeros, large patterns do not vanish, the
/// step-time plot is scaled to the bulk of the data, failures name the file
/// and leave nothing behind, and `esif run` writes the figures it should.

#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/render/FigureWriter.h>
#include <esif/render/MapOverlay.h>

#include <mrpt/img/CImage.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
using esif::InformationPattern;
using esif::MatrixPanel;
using esif::test::TempDir;
using Sparse = Eigen::SparseMatrix<double>;

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

Sparse identity(int n)
{
	Sparse m(n, n);
	m.setIdentity();
	return m;
}

mrpt::img::CImage load(const std::string& path)
{
	mrpt::img::CImage img;
	EXPECT_TRUE(img.loadFromFile(path)) << path;
	return img;
}

/// 0 = black, 1 = white, 2 = anything else.
int shade(const mrpt::img::CImage& img, int x, int y)
{
	const auto* px = img.ptr<uint8_t>(x, y);  // B, G, R
	if (px[0] == 0 && px[1] == 0 && px[2] == 0) return 0;
	if (px[0] == 255 && px[1] == 255 && px[2] == 255) return 1;
	return 2;
}

/// Counts panel pixels whose shade differs from black where `nonzero(i, j)`
/// for the matrix entry (i, j) they show (per MatrixPanel), white elsewhere.
int wrongPixels(const mrpt::img::CImage& img, const MatrixPanel& panel, int n, const std::function<bool(int, int)>& nonzero)
{
	int wrong = 0;
	for (int y = 0; y < panel.side_px; ++y)
		for (int x = 0; x < panel.side_px; ++x)
		{
			const int i = static_cast<int>(static_cast<long long>(y) * n / panel.side_px);
			const int j = static_cast<int>(static_cast<long long>(x) * n / panel.side_px);
			wrong += shade(img, panel.x0 + x, panel.y0 + y) != (nonzero(i, j) ? 0 : 1);
		}
	return wrong;
}

bool tridiagonal(int i, int j) { return std::abs(i - j) <= 1; }
bool lowerBidiagonal(int i, int j) { return i == j || i == j + 1; }

/// Folder entries (names), to check that a failed write left nothing.
std::vector<std::string> entries(const std::string& dir)
{
	std::vector<std::string> names;
	for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
	return names;
}

TEST(FigureWriter, SmallPatternIsBlackExactlyOnItsNonZeros)
{
	TempDir dir;
	InformationPattern p;
	p.information = pattern(10, tridiagonal);
	p.information.coeffRef(0, 9) = 0.0;	 // a stored zero is not a non-zero
	const auto panels = esif::informationPatternPanels(p, 400);
	ASSERT_EQ(panels.size(), 1u);
	EXPECT_EQ(panels[0].side_px % 10, 0) << "each entry should be an equal block";
	EXPECT_GE(panels[0].side_px, 300);

	esif::writeInformationPatternImage(p, dir.file("info.png"), 400);
	const auto img = load(dir.file("info.png"));
	EXPECT_EQ(img.getWidth(), 400u);
	EXPECT_EQ(img.getHeight(), 400u);
	EXPECT_EQ(wrongPixels(img, panels[0], 10, tridiagonal), 0);
}

TEST(FigureWriter, FactorIsDrawnBesideTheInformationMatrix)
{
	TempDir dir;
	InformationPattern p;
	p.information = pattern(10, tridiagonal);
	p.factor = pattern(10, lowerBidiagonal);
	p.factor_order = "natural order";
	const auto panels = esif::informationPatternPanels(p, 300);
	ASSERT_EQ(panels.size(), 2u);
	EXPECT_GE(panels[1].x0, 300) << "the factor panel is the right half";

	esif::writeInformationPatternImage(p, dir.file("info.png"), 300);
	const auto img = load(dir.file("info.png"));
	EXPECT_EQ(img.getWidth(), 600u);
	EXPECT_EQ(img.getHeight(), 300u);
	EXPECT_EQ(wrongPixels(img, panels[0], 10, tridiagonal), 0);
	EXPECT_EQ(wrongPixels(img, panels[1], 10, lowerBidiagonal), 0);
}

TEST(FigureWriter, LargeDiagonalStillShowsAsAnUnbrokenDiagonal)
{
	TempDir dir;
	InformationPattern p;
	p.information = identity(5000);
	const auto panels = esif::informationPatternPanels(p, 500);
	ASSERT_EQ(panels.size(), 1u);
	ASSERT_LT(panels[0].side_px, 5000);

	esif::writeInformationPatternImage(p, dir.file("info.png"), 500);
	const auto img = load(dir.file("info.png"));
	const MatrixPanel& q = panels[0];
	int diagonal_black = 0, off_diagonal_black = 0;
	for (int y = 0; y < q.side_px; ++y)
		for (int x = 0; x < q.side_px; ++x)
		{
			const bool black = shade(img, q.x0 + x, q.y0 + y) == 0;
			(x == y ? diagonal_black : off_diagonal_black) += black;
		}
	EXPECT_EQ(diagonal_black, q.side_px);
	EXPECT_EQ(off_diagonal_black, 0);
}

TEST(FigureWriter, SingleNonZeroInAHugeMatrixIsNotLost)
{
	TempDir dir;
	InformationPattern p;
	p.information.resize(100000, 100000);
	p.information.insert(77777, 12345) = 1e-300;
	esif::writeInformationPatternImage(p, dir.file("info.png"), 400);
	const auto img = load(dir.file("info.png"));
	const MatrixPanel q = esif::informationPatternPanels(p, 400)[0];
	const auto at = [&](long long i) { return static_cast<int>(i * q.side_px / 100000); };
	EXPECT_EQ(shade(img, q.x0 + at(12345), q.y0 + at(77777)), 0);
	int black = 0;
	for (int y = 0; y < q.side_px; ++y)
		for (int x = 0; x < q.side_px; ++x) black += shade(img, q.x0 + x, q.y0 + y) == 0;
	EXPECT_EQ(black, 1);
}

TEST(FigureWriter, EmptyMatricesStillGiveAnImage)
{
	TempDir dir;
	esif::writeInformationPatternImage(InformationPattern{}, dir.file("info.png"), 200);
	EXPECT_EQ(load(dir.file("info.png")).getWidth(), 200u);
	esif::writeStepTimesImage({}, {}, dir.file("steps.png"), 200);
	EXPECT_EQ(load(dir.file("steps.png")).getWidth(), 200u);
}

/// Colour classes of the step-time plot (palette: blue dots, red medians).
bool isBlue(const mrpt::img::CImage& img, int x, int y)
{
	const auto* px = img.ptr<uint8_t>(x, y);
	return px[0] > 180 && px[2] < 80 && px[1] < 120;
}
bool isRed(const mrpt::img::CImage& img, int x, int y)
{
	const auto* px = img.ptr<uint8_t>(x, y);
	return px[2] > 180 && px[1] < 60 && px[0] < 60;
}

TEST(FigureWriter, StepTimesImageHasTheRequestedWidthAndShowsDotsAndMedians)
{
	TempDir dir;
	// Time grows linearly with the map: 10 us per landmark, plus jitter.
	std::vector<double> us;
	std::vector<std::size_t> counts;
	for (std::size_t k = 0; k < 3000; ++k)
	{
		counts.push_back(k / 10);
		us.push_back(10.0 * counts.back() + 50.0 * (k % 7));
	}
	esif::writeStepTimesImage(us, counts, dir.file("steps.png"), 640);
	const auto img = load(dir.file("steps.png"));
	ASSERT_EQ(img.getWidth(), 640u);
	ASSERT_EQ(img.getHeight(), 480u);

	// Red median line: higher (smaller y) on the right than on the left.
	double left_y = 0, right_y = 0;
	int left_n = 0, right_n = 0, blue = 0;
	for (int y = 0; y < 480; ++y)
		for (int x = 0; x < 640; ++x)
		{
			blue += isBlue(img, x, y);
			if (!isRed(img, x, y)) continue;
			if (x < 200) left_y += y, ++left_n;
			if (x > 440) right_y += y, ++right_n;
		}
	EXPECT_GT(blue, 1000);
	ASSERT_GT(left_n, 0);
	ASSERT_GT(right_n, 0);
	EXPECT_GT(left_y / left_n, right_y / right_n + 100) << "the median line should climb to the right";
}

TEST(FigureWriter, StepTimeOutliersAreClippedSoTheBulkFillsThePlot)
{
	TempDir dir;
	// 1999 steps at 1-1.5 ms and one at 1 s: without clipping every dot
	// would sit on the bottom axis.
	std::vector<double> us(2000);
	for (std::size_t k = 0; k < us.size(); ++k) us[k] = 1000.0 + 10.0 * (k % 50);
	us[1234] = 1e6;
	std::vector<std::size_t> counts(2000);
	for (std::size_t k = 0; k < counts.size(); ++k) counts[k] = k / 20;
	esif::writeStepTimesImage(us, counts, dir.file("steps.png"), 800);
	const auto img = load(dir.file("steps.png"));
	// The bulk sits near the top of the time axis, which ends just
	// above it: nearly all blue pixels are in the upper half of the image.
	int blue = 0, blue_top = 0;
	const int h = static_cast<int>(img.getHeight());
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < static_cast<int>(img.getWidth()); ++x)
			if (isBlue(img, x, y)) ++blue, blue_top += y < h / 2;
	ASSERT_GT(blue, 200);
	EXPECT_GT(blue_top, blue * 9 / 10);
}

TEST(FigureWriter, LocalMapTimesShowBothLinesInBothPanels)
{
	TempDir dir;
	// Fusion time grows with the map index, association is half of it; the
	// state dimension grows too, so the per-dimension panel stays flatter.
	std::vector<esif::LocalMapFusionCost> costs;
	for (std::size_t k = 1; k <= 200; ++k)
		costs.push_back({k, 1e-4 * static_cast<double>(k), 0.5e-4 * static_cast<double>(k), 3 + 10 * k});
	esif::writeLocalMapTimesImage(costs, dir.file("lm.png"), 800);
	const auto img = load(dir.file("lm.png"));
	ASSERT_EQ(img.getWidth(), 800u);
	ASSERT_EQ(img.getHeight(), 600u);
	// Red (with association) and blue (without) in the upper and the lower panel.
	int red_top = 0, red_bottom = 0, blue_top = 0, blue_bottom = 0;
	for (int y = 0; y < 600; ++y)
		for (int x = 0; x < 800; ++x)
		{
			(y < 300 ? red_top : red_bottom) += isRed(img, x, y);
			(y < 300 ? blue_top : blue_bottom) += isBlue(img, x, y);
		}
	EXPECT_GT(red_top, 300);
	EXPECT_GT(red_bottom, 300);
	EXPECT_GT(blue_top, 300);
	EXPECT_GT(blue_bottom, 300);
	EXPECT_THROW(esif::writeLocalMapTimesImage(costs, dir.file("bad.png"), 100), esif::ConfigError);
	EXPECT_FALSE(fs::exists(dir.file("bad.png")));
}

TEST(FigureWriter, MapOverlayIsFramedOnTheReferenceWhateverAnotherRunDid)
{
	// The reference: a 40 m square loop with 16 landmarks beside it (black);
	// a run 1 m off it (red); a diverged run with one landmark 214 km away
	// (blue). The picture must stay on the reference: its black marks spread
	// over most of the plot, and both other runs show.
	esif::RunOutputs ref;
	for (int k = 0; k <= 160; ++k)
	{
		const double t = k / 40.0;	// side index and position along it
		const int side = std::min(3, static_cast<int>(t));
		const double u = 40.0 * (t - side);
		const double xy[4][2] = {{u, 0}, {40, u}, {40 - u, 40}, {0, 40 - u}};
		ref.trajectory.push_back({0.1 * k, {xy[side][0], xy[side][1], 0}});
	}
	for (int i = 0; i < 16; ++i)
		ref.landmarks.push_back({i, Eigen::Vector2d(2.5 * i + 1, i % 2 ? -3.0 : 43.0), Eigen::Matrix2d::Identity()});
	esif::RunOutputs close = ref, diverged = ref;
	for (auto& p : close.trajectory) p.pose.y += 1.0;
	for (auto& lm : close.landmarks) lm.mean.y() += 1.0;
	diverged.landmarks.back().mean = Eigen::Vector2d(2.14e5, 0);
	for (auto& p : diverged.trajectory) p.pose.x -= 1.0;
	TempDir dir;
	esif::writeMapOverlayImage({{"optimum", ref}, {"close", close}, {"diverged", diverged}}, "overlay",
							   dir.file("o.png"), 800);
	const auto img = load(dir.file("o.png"));
	ASSERT_EQ(img.getWidth(), 800u);
	ASSERT_EQ(img.getHeight(), 600u);
	int x_min = 800, x_max = 0, red = 0, blue = 0;
	for (int y = 0; y < 600; ++y)
		for (int x = 0; x < 800; ++x)
		{
			red += isRed(img, x, y);
			blue += isBlue(img, x, y);
			if (shade(img, x, y) == 0) x_min = std::min(x_min, x), x_max = std::max(x_max, x);
		}
	EXPECT_GT(x_max - x_min, 400);
	EXPECT_GT(red, 300);
	EXPECT_GT(blue, 300);
	EXPECT_THROW(esif::writeMapOverlayImage({}, "t", dir.file("none.png"), 800), esif::ConfigError);
	EXPECT_THROW(esif::writeMapOverlayImage({{"r", ref}}, "t", dir.file("small.png"), 100), esif::ConfigError);
	EXPECT_FALSE(fs::exists(dir.file("none.png")));
	EXPECT_FALSE(fs::exists(dir.file("small.png")));
}

TEST(FigureWriter, LineChartBreaksALineWhereAPointIsNotFinite)
{
	TempDir dir;
	// One panel, a red line at y = 0.5 over x in [0, 100] with a hole from
	// 40 to 60: red pixels on both sides of the hole, none inside it.
	// A blue line up to y = 2 puts the red one low in the plot, clear of the legend.
	esif::LineSeries line{"std", {}}, other{"other", {{0, 2}, {100, 2}}};
	for (int x = 0; x <= 100; ++x) line.points.emplace_back(x, x > 40 && x < 60 ? NAN : 0.5);
	esif::writeLineChartImage({"chart", "step", {{"sigma [m]", {line, other}}}}, dir.file("chart.png"), 800);
	const auto img = load(dir.file("chart.png"));
	ASSERT_EQ(img.getWidth(), 800u);
	std::vector<int> red_columns;
	for (int x = 0; x < 800; ++x)
		for (int y = 100; y < 600; ++y)	 // below the legend
			if (isRed(img, x, y))
			{
				red_columns.push_back(x);
				break;
			}
	ASSERT_FALSE(red_columns.empty());
	int widest_gap = 0;
	for (std::size_t i = 1; i < red_columns.size(); ++i) widest_gap = std::max(widest_gap, red_columns[i] - red_columns[i - 1]);
	// The plot is about 740 px wide for 100 units: a 20-unit hole is ~150 px.
	EXPECT_GT(widest_gap, 100);
	EXPECT_LT(widest_gap, 200);
	EXPECT_GT(red_columns.back() - red_columns.front(), 600);
}

TEST(FigureWriter, InvalidArgumentsAreRefusedBeforeWriting)
{
	TempDir dir;
	EXPECT_THROW(esif::writeStepTimesImage({1.0, 2.0}, {1}, dir.file("a.png"), 640), std::invalid_argument);
	EXPECT_THROW(esif::writeStepTimesImage({1.0}, {1}, dir.file("b.png"), 100), esif::ConfigError);
	EXPECT_THROW(esif::writeInformationPatternImage(InformationPattern{}, dir.file("c.png"), 20000), esif::ConfigError);
	EXPECT_TRUE(entries(dir.path()).empty());
}

TEST(FigureWriter, UnwritablePathThrowsInputErrorNamingItAndLeavesNothing)
{
	TempDir dir;
	InformationPattern p;
	p.information = identity(4);
	const std::string missing = dir.file("no/such/folder/info.png");
	try
	{
		esif::writeInformationPatternImage(p, missing, 300);
		FAIL() << "expected InputError";
	}
	catch (const esif::InputError& e)
	{
		EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
	}
	const std::string steps = dir.file("no/such/folder/steps.png");
	try
	{
		esif::writeStepTimesImage({1.0}, {1}, steps, 300);
		FAIL() << "expected InputError";
	}
	catch (const esif::InputError& e)
	{
		EXPECT_NE(std::string(e.what()).find(steps), std::string::npos) << e.what();
	}
	EXPECT_TRUE(entries(dir.path()).empty());

	// A folder in the way of the final name: the PNG is encoded, the rename
	// fails, and the temporary files are gone.
	fs::create_directory(dir.file("taken.png"));
	EXPECT_THROW(esif::writeInformationPatternImage(p, dir.file("taken.png"), 300), esif::InputError);
	EXPECT_THROW(esif::writeStepTimesImage({1.0}, {1}, dir.file("taken.png"), 300), esif::InputError);
	EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"taken.png"});
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
	EXPECT_FALSE(fs::exists(out + "/info_matrix.png")) << "the EKF has no information pattern";
	for (const auto& name : entries(out)) EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
}

}  // namespace
