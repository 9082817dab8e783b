// The Victoria Park importer: a lossless round trip through an MRPT rawlog,
// ID stripping, and one clear error per kind of malformed line.

#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/io/VictoriaParkImporter.h>

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
	EXPECT_NEAR(log.steps[1].odometry->delta.x, 0.000985144, 1e-12);
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

TEST(VictoriaParkImporter, MalformedLinesNameFileAndLine)
{
	EXPECT_NE(importError("ODOMETRY 0 1 0.1 0 0 1 0 0 1 0 1\nODOMETRY 1 2 0.1 0 zero 1 0 0 1 0 1\n").find("vp.txt:2: expected 'ODOMETRY"),
			  std::string::npos);
	EXPECT_NE(importError("ODOMETRY 0 1 0.1 0 0 1 0 0 1 0 1\nLANDMARK 1 5 3.0\n").find("vp.txt:2: expected 'LANDMARK"),
			  std::string::npos);
	EXPECT_NE(importError("ODOMETRY 0 1 0.1 0 0 1 0 0 1 0 1\nPOSE 1 2\n").find("vp.txt:2: unknown record 'POSE'"),
			  std::string::npos);
	EXPECT_NE(importError("ODOMETRY 0 1 0.1 0 0 1 0 0 1 0 1\nLANDMARK 7 5 3 1 0.4 0 0.4\n").find("vp.txt:2: pose 7 not defined"),
			  std::string::npos);
	EXPECT_NE(importError("ODOMETRY 0 1 0.1 0 0 1 0 0 1 0 1\nODOMETRY 5 6 0.1 0 0 1 0 0 1 0 1\n").find("vp.txt:2: odometry must start at the latest pose"),
			  std::string::npos);
	EXPECT_NE(importError("ODOMETRY 0 1 nan 0 0 1 0 0 1 0 1\n").find("vp.txt:1:"), std::string::npos);
	EXPECT_NE(importError("").find("no ODOMETRY records"), std::string::npos);
}

}  // namespace
