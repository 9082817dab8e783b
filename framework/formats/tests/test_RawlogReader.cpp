// Reading both MRPT rawlog formats, and every kind of bad rawlog.

#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/formats/RawlogReader.h>
#include <esif/formats/RawlogSteps.h>

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/serialization/CArchive.h>

#include <gtest/gtest.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace
{
using namespace esif;
using namespace mrpt::obs;

CActionCollection::Ptr odometryAction(double dx, double dphi)
{
	CActionRobotMovement2D mv;
	// With emOdometry MRPT stores only the raw reading and rebuilds the
	// Gaussian from its own motion model on reading; this keeps ours.
	mv.estimationMethod = CActionRobotMovement2D::emScan2DMatching;
	mrpt::math::CMatrixDouble33 cov;
	cov.setDiagonal(std::vector<double>{1e-4, 1e-4, 1e-5});
	mv.poseChange = mrpt::poses::CPosePDFGaussian::Create(mrpt::poses::CPose2D(dx, 0, dphi), cov);
	auto acts = CActionCollection::Create();
	acts->insert(mv);
	return acts;
}

CObservationBearingRange::Ptr scan(std::vector<std::pair<float, int>> range_id)
{
	auto obs = CObservationBearingRange::Create();
	obs->sensor_std_range = 0.1f;
	obs->sensor_std_yaw = 0.01f;
	obs->maxSensorDistance = 5;
	obs->fieldOfView_yaw = M_PI;
	for (const auto& [r, id] : range_id)
	{
		CObservationBearingRange::TMeasurement m;
		m.range = r;
		m.yaw = 0.1f;
		m.pitch = 0;
		m.landmarkID = id;
		obs->sensedData.push_back(m);
	}
	return obs;
}

CSensoryFrame::Ptr frameOf(const CObservation::Ptr& o)
{
	auto sf = CSensoryFrame::Create();
	sf->insert(o);
	return sf;
}

/// Actions/sensory-frames rawlog with `n` steps, gz-compressed.
void writeActionsSfLog(const std::string& path, int n, float bad_range = 1.0f)
{
	mrpt::io::CFileGZOutputStream f(path);
	auto ar = mrpt::serialization::archiveFrom(f);
	for (int k = 0; k < n; ++k)
		ar << *odometryAction(0.1, 0.01) << *frameOf(scan({{k == n - 1 ? bad_range : 1.0f, 7}, {2.0f, 8}}));
}

std::string errorOf(const std::string& path)
{
	try
	{
		readRawlog(path);
	}
	catch (const InputError& e)
	{
		return e.what();
	}
	return "";
}

TEST(RawlogReader, ActionsAndSensoryFrames)
{
	test::TempDir dir;
	writeActionsSfLog(dir.file("a.rawlog"), 5);
	const Rawlog log = readRawlog(dir.file("a.rawlog"));
	ASSERT_EQ(log.steps.size(), 5u);
	EXPECT_EQ(log.measurement_count, 10u);
	ASSERT_TRUE(log.steps[0].odometry && log.steps[0].scan);
	EXPECT_NEAR(log.steps[0].odometry->delta.x(), 0.1, 1e-12);
	EXPECT_NEAR(log.steps[0].odometry->cov(2, 2), 1e-5, 1e-15);
	EXPECT_EQ(log.steps[0].scan->measurements[0].id, 7);
	EXPECT_NEAR(log.steps[0].scan->measurements[0].cov(0, 0), 0.01, 1e-8);
	EXPECT_EQ(log.frames.size(), 5u);
	EXPECT_FALSE(log.truncation_warning);
}

TEST(RawlogReader, HiddenIdsAreKeptForScoring)
{
	test::TempDir dir;
	writeActionsSfLog(dir.file("a.rawlog"), 3);
	RawlogReadOptions opts;
	opts.hide_landmark_ids = true;
	const Rawlog log = readRawlog(dir.file("a.rawlog"), opts);
	EXPECT_FALSE(log.steps[1].scan->measurements[0].id);
	EXPECT_EQ(log.true_ids[1][0], 7);
}

TEST(RawlogReader, EachNoiseOverrideReplacesOnlyItsOwnVariance)
{
	test::TempDir dir;
	writeActionsSfLog(dir.file("a.rawlog"), 2);
	RawlogReadOptions range_only;
	range_only.sensor_std_range_m = 0.5;
	const auto r = readRawlog(dir.file("a.rawlog"), range_only).steps[0].scan->measurements[0].cov;
	EXPECT_NEAR(r(0, 0), 0.25, 1e-12);
	EXPECT_NEAR(r(1, 1), 1e-4, 1e-10);  // the rawlog's 0.01 rad
	RawlogReadOptions bearing_only;
	bearing_only.sensor_std_bearing_rad = 0.02;
	const auto b = readRawlog(dir.file("a.rawlog"), bearing_only).steps[0].scan->measurements[0].cov;
	EXPECT_NEAR(b(0, 0), 0.01, 1e-8);  // the rawlog's 0.1 m
	EXPECT_NEAR(b(1, 1), 4e-4, 1e-12);
	EXPECT_EQ(b(0, 1), 0.0);
}

TEST(RawlogReader, ObservationsOnlyWithAbsoluteOdometry)
{
	test::TempDir dir;
	const std::string path = dir.file("obs.rawlog");
	{
		mrpt::io::CFileOutputStream f(path);  // plain, not gz
		auto ar = mrpt::serialization::archiveFrom(f);
		for (int k = 0; k < 4; ++k)
		{
			CObservationOdometry odo;
			odo.odometry = mrpt::poses::CPose2D(0.5 * k, 0, 0.1 * k);
			ar << odo << *scan({{1.5f, 3}});
		}
	}
	const Rawlog log = readRawlog(path);
	// First reading only anchors the odometry: step 0 is a scan without odometry.
	ASSERT_EQ(log.steps.size(), 4u);
	EXPECT_FALSE(log.steps[0].odometry);
	ASSERT_TRUE(log.steps[2].odometry);
	// Increment between readings (0.5, 0, 0.1) and (1.0, 0, 0.2), in the first's frame.
	EXPECT_NEAR(log.steps[2].odometry->delta.x(), 0.5 * std::cos(0.1), 1e-12);
	EXPECT_NEAR(log.steps[2].odometry->delta(2), 0.1, 1e-12);
}

TEST(RawlogReader, TruncatedFileIsReadToItsLastCompleteStep)
{
	test::TempDir dir;
	writeActionsSfLog(dir.file("full.rawlog"), 20);
	// Decompressed copy cut in the middle of an entry.
	const Rawlog full = readRawlog(dir.file("full.rawlog"));
	const std::string plain = dir.file("plain.rawlog");
	{
		mrpt::io::CFileOutputStream f(plain);
		auto ar = mrpt::serialization::archiveFrom(f);
		for (int k = 0; k < 20; ++k) ar << *odometryAction(0.1, 0.01) << *frameOf(scan({{1.0f, 7}, {2.0f, 8}}));
	}
	const auto size = std::filesystem::file_size(plain);
	std::filesystem::resize_file(plain, size - size / 7);
	const Rawlog cut = readRawlog(plain);
	ASSERT_TRUE(cut.truncation_warning);
	EXPECT_NE(cut.truncation_warning->find("read up to step"), std::string::npos);
	EXPECT_GT(cut.steps.size(), 10u);
	EXPECT_LT(cut.steps.size(), full.steps.size());
	EXPECT_TRUE(cut.steps.back().scan.has_value());
}

TEST(RawlogReader, ALeanReadOfACutFileCountsTheStepsAFullReadKeeps)
{
	// 20 complete steps, then an odometry whose scan was cut in the middle:
	// the odometry-only step before the cut is dropped by both reads, and the
	// steps read again (RawlogSteps.h) are the steps kept.
	test::TempDir dir;
	const std::string plain = dir.file("cut.rawlog");
	{
		mrpt::io::CFileOutputStream f(plain);
		auto ar = mrpt::serialization::archiveFrom(f);
		for (int k = 0; k < 20; ++k) ar << *odometryAction(0.1, 0.01) << *frameOf(scan({{1.0f, 7}, {2.0f, 8}}));
		ar << *odometryAction(0.1, 0.01);
	}
	const auto complete = std::filesystem::file_size(plain);
	{
		mrpt::io::CFileOutputStream f(plain, mrpt::io::OpenMode::APPEND);
		auto ar = mrpt::serialization::archiveFrom(f);
		ar << *frameOf(scan({{1.0f, 7}, {2.0f, 8}}));
	}
	std::filesystem::resize_file(plain, complete + (std::filesystem::file_size(plain) - complete) / 2);

	const Rawlog kept = readRawlog(plain);
	RawlogReadOptions options;
	options.keep_steps = false;
	const Rawlog lean = readRawlog(plain, options);
	ASSERT_TRUE(kept.truncation_warning);
	EXPECT_EQ(lean.truncation_warning, kept.truncation_warning);
	ASSERT_EQ(kept.steps.size(), 20u);
	EXPECT_TRUE(kept.steps.back().scan.has_value());
	EXPECT_TRUE(lean.steps.empty());
	EXPECT_EQ(lean.stepCount(), 20u);
	EXPECT_EQ(lean.true_ids, kept.true_ids);
	EXPECT_EQ(lean.measurement_count, kept.measurement_count);
	ASSERT_TRUE(lean.source && kept.source);
	EXPECT_EQ(lean.source->steps_digest, kept.source->steps_digest);

	RawlogStepStream stream(*lean.source, "test");
	for (std::size_t k = 0; k < 20; ++k)
	{
		const RawlogStep& step = stream.next();
		EXPECT_EQ(step.input.index, k);
		ASSERT_TRUE(step.input.scan);
		EXPECT_EQ(step.input.scan->measurements.size(), 2u);
	}
	EXPECT_NO_THROW(stream.finish());
}

TEST(RawlogReader, MissingNotRawlogAndEmptyFilesAreErrors)
{
	test::TempDir dir;
	EXPECT_NE(errorOf(dir.file("none.rawlog")).find("not found"), std::string::npos);
	std::ofstream(dir.file("text.rawlog")) << "this is not a rawlog\n";
	EXPECT_NE(errorOf(dir.file("text.rawlog")).find("not an MRPT rawlog"), std::string::npos);
	std::ofstream(dir.file("empty.rawlog")).close();
	EXPECT_FALSE(errorOf(dir.file("empty.rawlog")).empty());
}

TEST(RawlogReader, NoOdometryOrNoObservationsAreErrors)
{
	test::TempDir dir;
	{
		mrpt::io::CFileGZOutputStream f(dir.file("noodo.rawlog"));
		auto ar = mrpt::serialization::archiveFrom(f);
		ar << *frameOf(scan({{1.0f, 1}}));
	}
	EXPECT_NE(errorOf(dir.file("noodo.rawlog")).find("no odometry"), std::string::npos);
	{
		mrpt::io::CFileGZOutputStream f(dir.file("noobs.rawlog"));
		auto ar = mrpt::serialization::archiveFrom(f);
		ar << *odometryAction(0.1, 0) << *CSensoryFrame::Create();
	}
	EXPECT_NE(errorOf(dir.file("noobs.rawlog")).find("no range-bearing"), std::string::npos);
}

TEST(RawlogReader, BadRangesNameTheEntryAndMeasurement)
{
	test::TempDir dir;
	for (float bad : {std::nanf(""), INFINITY, -1.0f, 3e38f})
	{
		writeActionsSfLog(dir.file("bad.rawlog"), 3, bad);
		const std::string err = errorOf(dir.file("bad.rawlog"));
		EXPECT_NE(err.find("entry 5, measurement 0: range"), std::string::npos) << err;
	}
}

TEST(RawlogReader, AnotherMrptObjectIsNamedNotReadAsAnEmptyRawlog)
{
	test::TempDir dir;
	{
		mrpt::maps::CSimpleMap map;
		mrpt::io::CFileGZOutputStream f(dir.file("map.simplemap"));
		auto ar = mrpt::serialization::archiveFrom(f);
		ar << map;
	}
	EXPECT_EQ(errorOf(dir.file("map.simplemap")),
			  dir.file("map.simplemap") +
				  ": entry 0: mrpt::maps::CSimpleMap is not a rawlog entry (a rawlog holds CActionCollection, "
				  "CSensoryFrame and CObservation objects)");
}

TEST(RawlogReader, NegativeLandmarkIdsAreRefusedNotAliased)
{
	// -1 is MRPT's "no ID"; any other negative ID was silently aliased by the
	// EKF's maps to landmark 0.
	test::TempDir dir;
	{
		mrpt::io::CFileGZOutputStream f(dir.file("neg.rawlog"));
		auto ar = mrpt::serialization::archiveFrom(f);
		ar << *odometryAction(0.1, 0) << *frameOf(scan({{1.0f, 3}, {2.0f, -1}}));
		ar << *odometryAction(0.1, 0) << *frameOf(scan({{1.0f, 3}, {2.0f, -7}}));
	}
	EXPECT_EQ(errorOf(dir.file("neg.rawlog")),
			  dir.file("neg.rawlog") + ": entry 3, measurement 1: landmark ID -7 is negative (IDs are >= 0; -1 means none)");
}

/// A one-step log whose odometry action carries `mean` and `cov` (kept as
/// given: not emOdometry, see odometryAction).
std::string errorOfOdometry(const test::TempDir& dir, const mrpt::poses::CPose2D& mean, const mrpt::math::CMatrixDouble33& cov)
{
	CActionRobotMovement2D mv;
	mv.estimationMethod = CActionRobotMovement2D::emScan2DMatching;
	mv.poseChange = mrpt::poses::CPosePDFGaussian::Create(mean, cov);
	auto acts = CActionCollection::Create();
	acts->insert(mv);
	{
		mrpt::io::CFileGZOutputStream f(dir.file("odo.rawlog"));
		auto ar = mrpt::serialization::archiveFrom(f);
		ar << *acts << *frameOf(scan({{1.0f, 3}}));
	}
	return errorOf(dir.file("odo.rawlog"));
}

/// MRPT reads estimationMethod as a raw integer: a value none of its
/// enumerators has is a corrupt entry, not an odometry to use.
TEST(RawlogReader, AnOdometryEnumOutsideMrptsValuesIsACorruptEntry)
{
	test::TempDir dir;
	for (const int method : {2, -1, 1000})
	{
		auto acts = odometryAction(0.1, 0.01);
		auto* mv = acts->getBestMovementEstimation().get();
		ASSERT_NE(mv, nullptr);
		static_assert(sizeof(mv->estimationMethod) == sizeof(method));
		std::memcpy(&mv->estimationMethod, &method, sizeof(method));  // as a corrupt file's bytes would set it
		{
			mrpt::io::CFileGZOutputStream f(dir.file("enum.rawlog"));
			auto ar = mrpt::serialization::archiveFrom(f);
			ar << *acts << *frameOf(scan({{1.0f, 3}}));
		}
		EXPECT_EQ(errorOf(dir.file("enum.rawlog")),
				  dir.file("enum.rawlog") + ": entry 0: odometry estimationMethod = " + std::to_string(method) +
					  " is none of MRPT's (0 odometry, 1 scan matching): a corrupt entry");
	}
}

TEST(RawlogReader, BadOdometryNamesTheEntryAndWhatIsWrong)
{
	test::TempDir dir;
	mrpt::math::CMatrixDouble33 good;
	good.setDiagonal(std::vector<double>{1e-4, 1e-4, 1e-5});
	EXPECT_EQ(errorOfOdometry(dir, mrpt::poses::CPose2D(0.1, 0, 0), good), "");
	const std::string where = dir.file("odo.rawlog") + ": entry 0: ";
	EXPECT_EQ(errorOfOdometry(dir, mrpt::poses::CPose2D(std::nan(""), 0, 0), good),
			  where + "odometry increment is not finite");
	EXPECT_EQ(errorOfOdometry(dir, mrpt::poses::CPose2D(1e300, 0, 0), good),
			  where + "odometry increment (1e+300, 0) is beyond 10000 m");
	mrpt::math::CMatrixDouble33 negative = good;
	negative(0, 0) = -1e-4;
	EXPECT_NE(errorOfOdometry(dir, mrpt::poses::CPose2D(0.1, 0, 0), negative)
				  .find(where + "odometry covariance is not positive semidefinite"),
			  std::string::npos);
	mrpt::math::CMatrixDouble33 indefinite = good;	// a correlation larger than both variances allow
	indefinite(0, 1) = indefinite(1, 0) = 1e-3;
	EXPECT_NE(errorOfOdometry(dir, mrpt::poses::CPose2D(0.1, 0, 0), indefinite)
				  .find(where + "odometry covariance is not positive semidefinite"),
			  std::string::npos);
}

TEST(RawlogReader, NonFiniteSensorPoseOrAbsoluteOdometryIsRefused)
{
	test::TempDir dir;
	{
		auto obs = scan({{1.0f, 3}});
		obs->sensorLocationOnRobot = mrpt::poses::CPose3D(std::nan(""), 0, 0, 0, 0, 0);
		mrpt::io::CFileGZOutputStream f(dir.file("sensor.rawlog"));
		auto ar = mrpt::serialization::archiveFrom(f);
		ar << *odometryAction(0.1, 0) << *frameOf(obs);
	}
	EXPECT_EQ(errorOf(dir.file("sensor.rawlog")),
			  dir.file("sensor.rawlog") + ": entry 1: sensor pose on the robot is not finite");
	{
		auto odo = CObservationOdometry::Create();
		odo->odometry = mrpt::poses::CPose2D(0, std::nan(""), 0);
		mrpt::io::CFileGZOutputStream f(dir.file("abs.rawlog"));
		auto ar = mrpt::serialization::archiveFrom(f);
		ar << *odo;
	}
	EXPECT_EQ(errorOf(dir.file("abs.rawlog")), dir.file("abs.rawlog") + ": entry 0: odometry reading is not finite");
}

}  // namespace
