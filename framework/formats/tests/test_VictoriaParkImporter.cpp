// The Victoria Park importer: a lossless round trip through an MRPT rawlog,
// ID stripping, and one clear error per kind of malformed line.

#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/formats/VictoriaParkImporter.h>

#include <gtest/gtest.h>
#include <cmath>
#include <fstream>
#include <set>

namespace
{
using namespace esif;

const std::string kDataset = test::sourcePath("../shared/data/victoria_park/victoria_park.txt");

std::string importError(const std::string& text)
{
	test::TempDir dir;
	std::ofstream(dir.file("vp.txt")) << text;
	try
	{
		importVictoriaPark(dir.file("vp.txt"), dir.file("vp.rawlog"), {});
	}
	catch (const InputError& e)
	{
		EXPECT_FALSE(std::filesystem::exists(dir.file("vp.rawlog")));  // nothing half-written
		return e.what();
	}
	return "";
}

TEST(VictoriaParkImporter, RoundTripKeepsPosesMeasurementsAndIds)
{
	if (!std::filesystem::exists(kDataset)) GTEST_SKIP() << kDataset << " not present";
	test::TempDir dir;
	const auto summary = importVictoriaPark(kDataset, dir.file("vp.rawlog"), {});
	EXPECT_EQ(summary.poses, 6969u);
	EXPECT_EQ(summary.measurements, 3640u);
	EXPECT_EQ(summary.landmark_ids, 151u);

	const Rawlog log = readRawlog(dir.file("vp.rawlog"));
	ASSERT_EQ(log.steps.size(), 6969u);
	EXPECT_EQ(log.measurement_count, 3640u);
	std::set<LandmarkId> ids;
	for (const auto& s : log.steps)
		for (const auto& m : s.scan->measurements)
		{
			ASSERT_TRUE(m.id);
			ids.insert(*m.id);
		}
	EXPECT_EQ(ids.size(), 151u);
	// First record "ODOMETRY 0 1 0.000985144 ... 0.0001 0 0 4e-06 0 4e-06" and
	// first landmark "LANDMARK 4 5 11.5387 -3.2007": step 4, landmark 5.
	EXPECT_NEAR(log.steps[1].odometry->delta.x(), 0.000985144, 1e-12);
	EXPECT_NEAR(log.steps[1].odometry->cov(0, 0), 1e-4, 1e-15);
	ASSERT_EQ(log.steps[4].scan->measurements.size(), 1u);
	const auto& m = log.steps[4].scan->measurements[0];
	EXPECT_EQ(*m.id, 5);
	EXPECT_NEAR(m.range_m, std::hypot(11.5387, -3.2007), 1e-5);	 // float storage
	EXPECT_NEAR(m.bearing_rad, std::atan2(-3.2007, 11.5387), 1e-6);
	EXPECT_NEAR(m.cov(0, 0), 0.25, 1e-7);  // default range noise 0.5 m
}

TEST(VictoriaParkImporter, NoIdsReallyStripsIds)
{
	if (!std::filesystem::exists(kDataset)) GTEST_SKIP() << kDataset << " not present";
	test::TempDir dir;
	VictoriaParkImportOptions opts;
	opts.keep_ids = false;
	importVictoriaPark(kDataset, dir.file("vp.rawlog"), opts);
	const Rawlog log = readRawlog(dir.file("vp.rawlog"));
	std::size_t n = 0;
	for (std::size_t k = 0; k < log.steps.size(); ++k)
		for (std::size_t i = 0; i < log.steps[k].scan->measurements.size(); ++i, ++n)
		{
			EXPECT_FALSE(log.steps[k].scan->measurements[i].id);
			EXPECT_FALSE(log.true_ids[k][i]);  // not in the file at all
		}
	EXPECT_EQ(n, 3640u);
}

/// The error for `text`, from its file name on ("vp.txt:LINE: ...").
std::string errorFrom(const std::string& text)
{
	const std::string e = importError(text);
	const auto at = e.find("vp.txt");
	return at == std::string::npos ? "(no file name) " + e : e.substr(at);
}

const std::string kFirst = "ODOMETRY 0 1 0.1 0 0 1 0 0 1 0 1\n";  // a valid first record

TEST(VictoriaParkImporter, MalformedLinesNameFileAndLine)
{
	EXPECT_EQ(
		errorFrom(kFirst + "ODOMETRY 1 2 0.1 0 zero 1 0 0 1 0 1\n"), "vp.txt:2: ODOMETRY dtheta = 'zero': not a number");
	EXPECT_EQ(
		errorFrom(kFirst + "LANDMARK 1 5 3.0\n"),
		"vp.txt:2: expected 'LANDMARK i l x y c11 c12 c22' (7 numbers), found 3");
	EXPECT_EQ(errorFrom(kFirst + "POSE 1 2\n"), "vp.txt:2: unknown record 'POSE' (expected ODOMETRY or LANDMARK)");
	EXPECT_EQ(errorFrom(kFirst + "LANDMARK 7 5 3 1 0.4 0 0.4\n"), "vp.txt:2: LANDMARK i = 7: pose not defined yet");
	EXPECT_EQ(
		errorFrom(kFirst + "ODOMETRY 5 6 0.1 0 0 1 0 0 1 0 1\n"),
		"vp.txt:2: ODOMETRY i = 5: odometry must start at the latest pose (1)");
	EXPECT_EQ(errorFrom(kFirst + "ODOMETRY 1 1 0.1 0 0 1 0 0 1 0 1\n"), "vp.txt:2: ODOMETRY j = 1: pose already exists");
	EXPECT_EQ(errorFrom("ODOMETRY 0 1 nan 0 0 1 0 0 1 0 1\n"), "vp.txt:1: ODOMETRY dx = 'nan': not a finite number");
	EXPECT_EQ(errorFrom(""), "vp.txt: no ODOMETRY records");
	// A LANDMARK line repeated: one scan cannot hold a landmark twice (MRPT
	// would refuse to write it, naming neither file nor line).
	EXPECT_EQ(
		errorFrom(kFirst + "LANDMARK 1 5 3 1 0.4 0 0.4\nLANDMARK 1 5 3 1 0.4 0 0.4\n"),
		"vp.txt:3: LANDMARK 1 5: landmark 5 is measured twice from pose 1 (first on line 2): a repeated line");
}

TEST(VictoriaParkImporter, ImplausibleNumbersAreRejectedAtTheBorder)
{
	// Each line differs from a valid record in one field.
	EXPECT_EQ(
		errorFrom(kFirst + "ODOMETRY 1 2 0.1 0 0 -1 0 0 1 0 1\n"),
		"vp.txt:2: ODOMETRY c11 = -1: a variance must be in (0, 1e+06]");
	EXPECT_EQ(
		errorFrom(kFirst + "ODOMETRY 1 2 1e300 0 0 1 0 0 1 0 1\n"),
		"vp.txt:2: ODOMETRY dx = 1e+300: must be within +-100 m (longest plausible odometry step)");
	EXPECT_EQ(
		errorFrom(kFirst + "ODOMETRY 1 2 0.1 0 90 1 0 0 1 0 1\n"),
		"vp.txt:2: ODOMETRY dtheta = 90: must be within +-6.283 rad (one full turn; degrees instead of radians?)");
	EXPECT_EQ(
		errorFrom(kFirst + "LANDMARK 1 5 1e300 1 0.4 0 0.4\n"),
		"vp.txt:2: LANDMARK x = 1e+300: must be within +-1000 m (farthest plausible landmark)");
	EXPECT_EQ(
		errorFrom(kFirst + "LANDMARK 1 5 0 0 0.4 0 0.4\n"),
		"vp.txt:2: LANDMARK x, y = 0, 0: 0 m from the sensor, nearer than 0.001 m (bearing undefined)");
	EXPECT_EQ(
		errorFrom(kFirst + "LANDMARK 1 5 40 0 0.4 0 0.4\n"),
		"vp.txt:2: LANDMARK x, y = 40, 0: range 40 m beyond the sensor range --max-range-m = 30 m");
	// Positive variances, but c12 makes the 2x2 matrix indefinite
	// (eigenvalues 0.4 -+ 1).
	EXPECT_EQ(
		errorFrom(kFirst + "LANDMARK 1 5 3 1 0.4 1 0.4\n"),
		"vp.txt:2: LANDMARK covariance (c11 c12 c22) = (0.4 1 0.4): eigenvalues -0.6 to 1.4, must be in [1e-12, "
		"1e+06] (positive definite, finite)");
	EXPECT_EQ(
		errorFrom(kFirst + "ODOMETRY 1 2 0.1 0 0 1 0 0 1 0 1e-300\n"),
		"vp.txt:2: ODOMETRY covariance (c11 c12 c13 c22 c23 c33) = (1 0 0 1 0 1e-300): eigenvalues 1e-300 to 1, must "
		"be in [1e-12, 1e+06] (positive definite, finite)");
	// Node IDs: fractional, negative, beyond MRPT's int32 landmark IDs.
	EXPECT_EQ(
		errorFrom(kFirst + "ODOMETRY 1 2.5 0.1 0 0 1 0 0 1 0 1\n"),
		"vp.txt:2: ODOMETRY j = 2.5: a node ID must be an integer in [0, 2147483647]");
	EXPECT_EQ(
		errorFrom(kFirst + "LANDMARK 1 -5 3 1 0.4 0 0.4\n"),
		"vp.txt:2: LANDMARK l = -5: a node ID must be an integer in [0, 2147483647]");
	EXPECT_EQ(
		errorFrom(kFirst + "LANDMARK 1 3e9 3 1 0.4 0 0.4\n"),
		"vp.txt:2: LANDMARK l = 3e+09: a node ID must be an integer in [0, 2147483647]");
}

TEST(VictoriaParkImporter, ImplausibleOptionsNameTheOption)
{
	test::TempDir dir;
	std::ofstream(dir.file("vp.txt")) << kFirst;
	VictoriaParkImportOptions options;
	options.std_range_m = 1e300;
	try
	{
		importVictoriaPark(dir.file("vp.txt"), dir.file("vp.rawlog"), options);
		ADD_FAILURE() << "no error";
	}
	catch (const ConfigError& e)
	{
		EXPECT_STREQ(
			e.what(),
			"import victoria-park: --std-range-m = 1e+300: must be in [1e-06, 100] (below a micrometre no sensor "
			"measures; beyond 100 m a measurement carries no information)");
	}
	// A subnormal noise passes "> 0" and squares to a zero variance in the rawlog.
	options.std_range_m = 1e-320;
	EXPECT_THROW(importVictoriaPark(dir.file("vp.txt"), dir.file("vp.rawlog"), options), ConfigError);
	options.std_range_m = 0.5;
	options.std_bearing_deg = 1e-7;
	EXPECT_THROW(importVictoriaPark(dir.file("vp.txt"), dir.file("vp.rawlog"), options), ConfigError);
	// A valid file still imports (the bounds leave the dataset's values alone).
	const auto summary = importVictoriaPark(dir.file("vp.txt"), dir.file("vp.rawlog"), {});
	EXPECT_EQ(summary.poses, 2u);
}

}  // namespace
