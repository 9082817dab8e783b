#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/io/GroundTruth.h>

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

TEST(GroundTruth, MalformedFileNamesFileAndLine)
{
	test::TempDir dir;
	std::ofstream(dir.file("g_ground_truth.txt")) << "1 2 0 5 0 0 1\n1 2 zero 5 0 0 2\n";
	try
	{
		loadGroundTruth(dir.file("g"));
		FAIL();
	}
	catch (const InputError& e)
	{
		EXPECT_NE(std::string(e.what()).find("g_ground_truth.txt:2:"), std::string::npos) << e.what();
	}
}

}  // namespace
