#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/formats/GroundTruth.h>

#include <gtest/gtest.h>
#include <fstream>

namespace
{
using namespace esif;

TEST(GroundTruth, ReadsMrptFilesOfKfSlamDemo)
{
	const auto gt = loadGroundTruth(std::string(ESIF_MRPT_DATASETS) + "/kf-slam_demo");
	ASSERT_TRUE(gt);
	EXPECT_EQ(gt->landmarks.size(), 70u);
	EXPECT_EQ(gt->path.size(), 250u);
	EXPECT_NEAR(gt->landmarks.at(1).x(), 0.578229, 1e-9);
}

TEST(GroundTruth, SaveLoadRoundTripAndPrefix)
{
	test::TempDir dir;
	GroundTruth gt;
	gt.landmarks[3] = {1.5, -2.25};
	gt.landmarks[10] = {-0.125, 4.0};
	gt.path = {Pose2(1, 2, 0.5), Pose2(1.5, 2.5, -3.0)};
	const auto prefix = groundTruthPrefixFor(dir.file("x.rawlog"));
	EXPECT_EQ(prefix, dir.file("x"));
	saveGroundTruth(gt, prefix);
	const auto back = loadGroundTruth(prefix);
	ASSERT_TRUE(back);
	EXPECT_EQ(back->landmarks.size(), 2u);
	EXPECT_NEAR((back->landmarks.at(10) - gt.landmarks.at(10)).norm(), 0, 1e-6);
	ASSERT_EQ(back->path.size(), 2u);
	EXPECT_NEAR((back->path[1] - gt.path[1]).norm(), 0, 1e-12);
}

TEST(GroundTruth, InitialPoseFrameStartsAtOrigin)
{
	GroundTruth gt;
	gt.path = {Pose2(2, 3, M_PI / 2), Pose2(2, 4, M_PI / 2)};
	gt.landmarks[0] = {2, 5};
	const auto rel = gt.inInitialPoseFrame();
	EXPECT_NEAR(rel.path[0].norm(), 0, 1e-12);
	EXPECT_NEAR((rel.path[1] - Pose2(1, 0, 0)).norm(), 0, 1e-12);
	EXPECT_NEAR((rel.landmarks.at(0) - Eigen::Vector2d(2, 0)).norm(), 0, 1e-12);
}

/// The error loading ground truth whose landmark file is `landmarks` (and
/// path file `path`, when given), from the file name on.
std::string loadError(const std::string& landmarks, const std::string& path = "")
{
	test::TempDir dir;
	std::ofstream(dir.file("g_ground_truth.txt")) << landmarks;
	if (!path.empty()) std::ofstream(dir.file("g_ground_truth_robot_path.txt")) << path;
	try
	{
		loadGroundTruth(dir.file("g"));
	}
	catch (const InputError& e)
	{
		const std::string what = e.what();
		const auto at = what.find("g_ground_truth");
		return at == std::string::npos ? "(no file name) " + what : what.substr(at);
	}
	return "(no error)";
}

const std::string kLandmark1 = "1 2 0 5 0 0 1\n";  // a valid landmark, ID 1

TEST(GroundTruth, MalformedFileNamesFileLineAndColumn)
{
	EXPECT_EQ(
		loadError(kLandmark1 + "1 2 zero 5 0 0 2\n"), "g_ground_truth.txt:2: column 3 (z) = 'zero': not a number");
	// A fractional ID was rounded into a "duplicate" of ID 1.
	EXPECT_EQ(
		loadError(kLandmark1 + "3 4 0 5 0 0 1.4\n"),
		"g_ground_truth.txt:2: column 7 (ID) = 1.4: a landmark ID must be an integer, not fractional");
	EXPECT_EQ(
		loadError(kLandmark1 + "3 4 0 5 0 0 -2\n"),
		"g_ground_truth.txt:2: column 7 (ID) = -2: a landmark ID must be in [0, 2147483647]");
	EXPECT_EQ(
		loadError(kLandmark1 + "3 4 0 5 0 0 1\n"),
		"g_ground_truth.txt:2: column 7 (ID) = 1: duplicate landmark ID (first on line 1)");
	EXPECT_EQ(
		loadError(kLandmark1 + "inf 4 0 5 0 0 2\n"), "g_ground_truth.txt:2: column 1 (x) = 'inf': not a finite number");
	EXPECT_EQ(
		loadError(kLandmark1 + "3 1e300 0 5 0 0 2\n"),
		"g_ground_truth.txt:2: column 2 (y) = 1e+300: must be within +-1e+07 m (a corrupt file or the wrong units)");
	EXPECT_EQ(
		loadError(kLandmark1 + "3 4 0 5 0 2\n"),
		"g_ground_truth.txt:2: too few values: expected 7 columns 'x y z type seenCount tLastSeen ID', found 6");
	// The robot path: the same rules for its columns.
	EXPECT_EQ(
		loadError(kLandmark1, "% comment\n1 2 0 0.5 0 0\n1 2 0 nan 0 0\n"),
		"g_ground_truth_robot_path.txt:3: column 4 (yaw) = 'nan': not a finite number");
	EXPECT_EQ(
		loadError(kLandmark1, "1 2 0 0.5 0\n"),
		"g_ground_truth_robot_path.txt:1: too few values: expected 6 columns 'x y z yaw pitch roll', found 5");
	EXPECT_EQ(
		loadError(kLandmark1, "-2e7 2 0 0.5 0 0\n"),
		"g_ground_truth_robot_path.txt:1: column 1 (x) = -2e+07: must be within +-1e+07 m (a corrupt file or the wrong "
		"units)");
	EXPECT_EQ(loadError(kLandmark1, "1 2 0 0.5 0 0\n"), "(no error)");
}

}  // namespace
