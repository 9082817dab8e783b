// esif import mrclam (MrclamImporter.h): the first steps of robot 1 of
// dataset 6 against values computed independently from the files (numpy:
// exact unicycle arcs over the commands, Vicon interpolated), and a small
// synthetic recording in the MRCLAM format for the rules: dropped robots and
// unknown barcodes, steps per distinct time, and one FILE:LINE error per
// malformed line.

#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/MrclamImporter.h>
#include <esif/formats/RawlogReader.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace
{
using namespace esif;
using test::TempDir;

// ------------------------------------------------------------ robot 1 of dataset 6

TEST(MrclamImporter, FirstStepsOfRobot1MatchAnIndependentComputation)
{
	const std::string dataset = test::mrclamDataset();
	if (!fs::exists(dataset)) GTEST_SKIP() << dataset << " not present";
	TempDir dir;
	const auto summary = importMrclam(dataset, dir.file("r1.rawlog"), MrclamImportOptions{});
	EXPECT_EQ(summary.steps, 1012u);
	EXPECT_EQ(summary.measurements, 1534u);
	EXPECT_EQ(summary.robot_measurements, 407u);
	EXPECT_EQ(summary.unknown_barcodes, 1u);  // barcode 43, in no subject's row
	EXPECT_EQ(summary.landmarks, 15u);
	EXPECT_NEAR(summary.longest_gap_s, 52.641, 1e-6);

	const Rawlog log = readRawlog(dir.file("r1.rawlog"));
	ASSERT_EQ(log.steps.size(), 1012u);
	EXPECT_NEAR(log.steps[0].time_s, 1248444189.599, 1e-6);
	EXPECT_FALSE(log.steps[0].odometry && log.steps[0].odometry->delta.x() != 0);
	ASSERT_TRUE(log.steps[0].scan && !log.steps[0].scan->measurements.empty());
	const auto& first = log.steps[0].scan->measurements[0];
	EXPECT_EQ(first.id.value_or(-1), 15);  // barcode 90 is subject 15
	EXPECT_NEAR(first.range_m, 6.758, 1e-6);
	EXPECT_NEAR(first.bearing_rad, -0.005, 1e-6);

	// Odometry integrated over the commands between the step times.
	const std::vector<std::pair<std::size_t, Eigen::Vector3d>> odometry = {
		{1, {0.015571771, -0.000075769, -0.008869004}},
		{2, {0.012375925, -0.000036039, -0.005823997}},
		{3, {0, 0, 0}},	 // commanded to stand
		{100, {0.015812004, 0, 0}}};
	for (const auto& [k, expected] : odometry)
	{
		ASSERT_TRUE(log.steps[k].odometry) << k;
		const auto& d = log.steps[k].odometry->delta;
		EXPECT_NEAR(d.x(), expected.x(), 1e-8) << k;
		EXPECT_NEAR(d.y(), expected.y(), 1e-8) << k;
		EXPECT_NEAR(d(2), expected.z(), 1e-8) << k;
	}
	// Standing for 0.460 s (heading 0 in the step's frame): the floor and the
	// random walks q_v dt along x and r0 dt in heading, nothing else.
	const VelocityNoise noise;
	const Eigen::Matrix3d still = log.steps[3].odometry->cov;
	EXPECT_NEAR(still(0, 0), noise.floor_m * noise.floor_m + noise.speed_psd * 0.460, 1e-10);
	EXPECT_NEAR(still(1, 1), noise.floor_m * noise.floor_m, 1e-12);
	EXPECT_NEAR(still(2, 2), noise.turn_psd * 0.460, 1e-9);
	// The covariance grows with the blind time: the 52.6 s gap against a 0.23 s step.
	std::size_t gap_step = 0;
	for (std::size_t k = 1; k < log.steps.size(); ++k)
		if (log.steps[k].time_s - log.steps[k - 1].time_s > 52) gap_step = k;
	ASSERT_GT(gap_step, 0u);
	EXPECT_GT(log.steps[gap_step].odometry->cov.trace(), 1000 * log.steps[1].odometry->cov.trace());

	// Ground truth in the frame of the true first pose.
	const auto truth = loadGroundTruth(groundTruthPrefixFor(dir.file("r1.rawlog")));
	ASSERT_TRUE(truth);
	ASSERT_EQ(truth->path.size(), 1012u);
	EXPECT_EQ(truth->path[0], Pose2::Zero());
	EXPECT_TRUE(truth->path[1].isApprox(Pose2(0.014683254, 0.000719102, -0.001120006), 1e-7)) << truth->path[1];
	EXPECT_TRUE(truth->path[100].isApprox(Pose2(2.598919543, 0.117998182, 0.076599996), 1e-8)) << truth->path[100];
	// Landmarks in CLandmarksMap's text format: 6 decimals.
	ASSERT_EQ(truth->landmarks.size(), 15u);
	EXPECT_LT((truth->landmarks.at(6) - Eigen::Vector2d(-0.491222982, 0.781751103)).cwiseAbs().maxCoeff(), 5e-7);
	EXPECT_LT((truth->landmarks.at(20) - Eigen::Vector2d(8.268286060, 0.305867121)).cwiseAbs().maxCoeff(), 5e-7);
}

// ------------------------------------------------------------ a synthetic recording

/// A recording of robot 1 in the MRCLAM layout: three landmark subjects,
/// one robot, one unknown barcode; the robot drives 1 m straight in 10 s.
class SyntheticRecording : public ::testing::Test
{
   protected:
	void SetUp() override
	{
		write("Barcodes.dat", "# Subject # Barcode #\n1 5\n2 14\n6 63\n7 81\n8 7\n");
		write("Landmark_Groundtruth.dat", "# header\n6 1.0 2.0 0.001 0.001\n7 3.0 -1.0 0.001 0.001\n8 5.0 0.5 0 0\n");
		write("Robot1_Odometry.dat", "# Time v w\n100.0 0.1 0.0\n110.0 0.0 0.0\n");
		write("Robot1_Measurement.dat",
			  "# Time barcode range bearing\n101.0 63 2.0 0.5\n101.0 81 3.0 -0.2\n101.0 14 1.5 0.0\n"
			  "104.0 7 4.0 0.1\n104.5 43 2.0 0.0\n106.0 63 1.0 1.0\n");
		write("Robot1_Groundtruth.dat", "# Time x y theta\n99.0 0.0 0.0 0.0\n111.0 1.2 0.0 0.0\n");
	}

	void write(const std::string& name, const std::string& text) const { std::ofstream(dir_.file(name)) << text; }
	std::string file(const std::string& name) const { return dir_.file(name); }

	/// The InputError of importing, or "" when it succeeds.
	std::string importError() const
	{
		try
		{
			importMrclam(dir_.path(), out_.file("r.rawlog"), MrclamImportOptions{});
		}
		catch (const InputError& e)
		{
			return e.what();
		}
		return "";
	}

	TempDir dir_, out_;
};

TEST_F(SyntheticRecording, OneStepPerLandmarkTimeRobotsAndUnknownBarcodesDropped)
{
	const auto s = importMrclam(dir_.path(), out_.file("r.rawlog"), MrclamImportOptions{});
	EXPECT_EQ(s.steps, 3u);	 // 101 (two landmarks, one robot), 104, 106; 104.5 is barcode 43
	EXPECT_EQ(s.measurements, 4u);
	EXPECT_EQ(s.robot_measurements, 1u);
	EXPECT_EQ(s.unknown_barcodes, 1u);
	EXPECT_EQ(s.landmarks, 3u);
	const Rawlog log = readRawlog(out_.file("r.rawlog"));
	ASSERT_EQ(log.steps.size(), 3u);
	ASSERT_EQ(log.steps[0].scan->measurements.size(), 2u);
	EXPECT_EQ(log.steps[0].scan->measurements[1].id.value_or(-1), 7);
	// 0.1 m/s for the 3 s from 101 to 104 (commands held from 100 s).
	EXPECT_NEAR(log.steps[1].odometry->delta.x(), 0.3, 1e-12);
	EXPECT_NEAR(log.steps[2].odometry->delta.x(), 0.2, 1e-12);
	// Truth: the robot's 1.2 m in 12 s of Vicon, in the frame of the pose at 101 s (x = 0.2 m).
	const auto truth = loadGroundTruth(groundTruthPrefixFor(out_.file("r.rawlog")));
	ASSERT_TRUE(truth);
	EXPECT_TRUE(truth->path[1].isApprox(Pose2(0.3, 0, 0), 1e-12)) << truth->path[1];
	EXPECT_TRUE(truth->landmarks.at(8).isApprox(Eigen::Vector2d(4.8, 0.5), 1e-12));

	MrclamImportOptions no_ids;
	no_ids.keep_ids = false;
	importMrclam(dir_.path(), out_.file("n.rawlog"), no_ids);
	EXPECT_FALSE(readRawlog(out_.file("n.rawlog")).steps[0].scan->measurements[0].id.has_value());
}

TEST_F(SyntheticRecording, EveryMalformedLineIsOneErrorNamingFileAndLine)
{
	const std::string odometry = "# Time v w\n100.0 0.1 0.0\n";
	const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
		{"Robot1_Odometry.dat", odometry + "110.0 0.0\n", ":3: too few values: expected 3 columns 'time v w', found 2"},
		{"Robot1_Odometry.dat", odometry + "99.0 0.0 0.0\n", ":3: column 1 (time) = 99: goes back in time"},
		{"Robot1_Odometry.dat", odometry + "110.0 50 0.0\n", ":3: column 2 (v) = 50: must be in [-10, 10] m/s"},
		{"Robot1_Odometry.dat", odometry + "110.0 nan 0.0\n", ":3: column 2 (v) = 'nan': not a finite number"},
		{"Robot1_Measurement.dat", "101.0 63 0 0.5\n", ":1: column 3 (range) = 0: must be in [0.001, 100] m"},
		{"Robot1_Measurement.dat", "101.0 63 2.0 4\n", ":1: column 4 (bearing) = 4: must be in"},
		{"Robot1_Measurement.dat", "101.0 6.5 2.0 0\n", ":1: column 2 (barcode) = 6.5: must be a whole number"},
		{"Barcodes.dat", "1 5\n1 14\n", ":2: column 1 (subject) = 1: subject listed twice"},
		{"Barcodes.dat", "1 5\n21 14\n", ":2: column 1 (subject) = 21: must be in [1, 20]"},
		{"Landmark_Groundtruth.dat", "6 1e9 2.0 0 0\n", ":1: column 2 (x) = 1e+09: must be within +-1e+07 m"},
		{"Robot1_Groundtruth.dat", "99.0 0 0 0\n100.5 0 0 1e300\n", ":2: column 4 (theta) = 1e+300: must be within"},
		// A repeated line: one barcode read twice in one image.
		{"Robot1_Measurement.dat", "101.0 63 2.0 0.5\n101.0 63 2.0 0.5\n",
		 ":2: column 2 (barcode) = 63: read twice at the same time (first on line 1): a repeated line"},
	};
	for (const auto& [name, text, expected] : cases)
	{
		SetUp();
		write(name, text);
		const std::string error = importError();
		EXPECT_EQ(error.rfind(file(name) + expected, 0), 0u) << name << ": " << error;
	}
	// A step the ground truth does not cover; a missing file; no landmark measured.
	SetUp();
	write("Robot1_Groundtruth.dat", "102.0 0 0 0\n111.0 1 0 0\n");
	EXPECT_EQ(importError().rfind(file("Robot1_Groundtruth.dat") + ": the ground truth covers 102 to 111 s, not the step at 101 s", 0), 0u)
		<< importError();
	SetUp();
	fs::remove(file("Robot1_Odometry.dat"));
	EXPECT_EQ(importError(), file("Robot1_Odometry.dat") + ": MRCLAM odometry not found");
	SetUp();
	write("Robot1_Measurement.dat", "101.0 14 1.5 0.0\n");
	EXPECT_EQ(importError(), file("Robot1_Measurement.dat") + ": no measurement of a landmark (subjects 6-20)");
	EXPECT_FALSE(fs::exists(out_.file("r.rawlog"))) << "nothing written by a failed import";
}

/// An odometry file cut short: its last command would be held for the rest
/// of the recording, as if the robot had been told to keep driving.
TEST_F(SyntheticRecording, AnOdometryFileThatEndsLongBeforeTheMeasurementsIsRefused)
{
	write("Robot1_Odometry.dat", "# Time v w\n100.0 0.1 0.0\n100.5 0.1 0.0\n");
	write("Robot1_Measurement.dat", "101.0 63 2.0 0.5\n110.0 81 3.0 -0.2\n");
	EXPECT_EQ(importError().rfind(
				  file("Robot1_Odometry.dat") + ": its last velocity command is at 100.5 s, but the measurements go on "
												"for 9.5 s more: the file is cut short",
				  0),
			  0u)
		<< importError();
	SetUp();
	write("Robot1_Odometry.dat", "# Time v w\n108.0 0.1 0.0\n110.0 0.0 0.0\n");
	EXPECT_NE(importError().find("its first velocity command is at 108 s, 7.0 s after the first measurement"),
			  std::string::npos)
		<< importError();
}

TEST_F(SyntheticRecording, TheCommandChecksItsOptionsAndNeverWritesIntoTheRecording)
{
	const std::string base = "import mrclam --dataset " + test::quoted(dir_.path()) + " ";
	test::expectOneErrorLine(test::runEsif(base + "--robot 6 --out " + test::quoted(out_.file("r.rawlog"))),
							 "--robot 6: must be 1 to 5");
	test::expectOneErrorLine(
		test::runEsif(base + "--robot 1 --odometry-speed-scale -1 --out " + test::quoted(out_.file("r.rawlog"))),
		"--odometry-speed-scale = -1: must be in [0, 1000]");
	// Subnormal noise passes "> 0" and becomes a zero variance in the rawlog.
	test::expectOneErrorLine(
		test::runEsif(base + "--robot 1 --std-range-m 1e-320 --out " + test::quoted(out_.file("r.rawlog"))),
		"--std-range-m = ");
	test::expectOneErrorLine(
		test::runEsif(base + "--robot 1 --odometry-floor-m 1e-320 --out " + test::quoted(out_.file("r.rawlog"))),
		"--odometry-floor-m = ");
	test::expectOneErrorLine(test::runEsif(base + "--robot 1 --out " + test::quoted(file("r.rawlog"))),
							 "--out lies inside the MRCLAM recording");
	const auto ok = test::runEsif(base + "--robot 1 --out " + test::quoted(out_.file("r.rawlog")));
	EXPECT_EQ(ok.exit_code, 0) << ok.out;
	EXPECT_NE(ok.out.find("3 steps"), std::string::npos) << ok.out;
}

}  // namespace
