/// The calibration file and what applying it does to a step.

#include <EsifTestSupport.h>
#include <esif/calibration/NoiseCalibration.h>
#include <esif/core/Errors.h>
#include <esif/safeio/AtomicFile.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace esif;

namespace
{
StepInput stepWithOdometryAndScan()
{
	StepInput step;
	step.index = 7;
	step.odometry = OdometryIncrement{{2.0, 0.0, 0.1}, Eigen::Vector3d(1e-4, 4e-6, 4e-6).asDiagonal()};
	Scan scan;
	RangeBearing m;
	m.range_m = 10;
	m.bearing_rad = 0.5;
	m.cov = Eigen::Vector2d(0.25, 0.001).asDiagonal();
	scan.measurements = {m};
	step.scan = scan;
	return step;
}
}  // namespace

TEST(NoiseCalibration, IdentityChangesNothing)
{
	const NoiseCalibration identity;
	EXPECT_TRUE(identity.isIdentity());
	const StepInput step = stepWithOdometryAndScan();
	const StepInput out = calibratedStep(step, identity);
	EXPECT_EQ(out.odometry->delta, step.odometry->delta);
	EXPECT_EQ(out.odometry->cov, step.odometry->cov);
	EXPECT_EQ(out.scan->measurements[0].range_m, 10);
	EXPECT_EQ(out.scan->measurements[0].cov, step.scan->measurements[0].cov);
}

TEST(NoiseCalibration, ScalesOdometryAndTakesOutItsSystematicErrors)
{
	NoiseCalibration c;
	c.odometry_std_scale_xy = 3;
	c.odometry_std_scale_phi = 2;
	c.odometry_distance_scale = 1.1;
	c.odometry_turn_scale = 1.05;
	c.odometry_heading_drift_deg_per_m = 0.5;
	const StepInput out = calibratedStep(stepWithOdometryAndScan(), c);
	EXPECT_NEAR(out.odometry->delta.x(), 2.2, 1e-12);
	// dphi' = 1.05 * 0.1 + 0.5 deg/m * 2 m
	EXPECT_NEAR(out.odometry->delta(2), 0.105 + 1.0 * M_PI / 180, 1e-12);
	EXPECT_NEAR(out.odometry->cov(0, 0), 9e-4, 1e-15);
	EXPECT_NEAR(out.odometry->cov(1, 1), 36e-6, 1e-15);
	EXPECT_NEAR(out.odometry->cov(2, 2), 16e-6, 1e-15);
}

TEST(NoiseCalibration, DriftFollowsTheDirectionOfTravel)
{
	NoiseCalibration c;
	c.odometry_heading_drift_deg_per_m = 1;
	StepInput step = stepWithOdometryAndScan();
	step.odometry->delta = {-2.0, 0.0, 0.0};  // reversing 2 m
	EXPECT_NEAR(calibratedStep(step, c).odometry->delta(2), -2 * M_PI / 180, 1e-12);
}

TEST(NoiseCalibration, TakesOutTheSensorBiasAndReplacesItsNoise)
{
	NoiseCalibration c;
	c.range_bias_m = 0.2;
	c.bearing_bias_deg = 1;
	c.range_std_m = 0.1;
	c.bearing_std_deg = 0.5;
	const auto m = calibratedStep(stepWithOdometryAndScan(), c).scan->measurements[0];
	EXPECT_NEAR(m.range_m, 9.8, 1e-12);
	EXPECT_NEAR(m.bearing_rad, 0.5 - M_PI / 180, 1e-12);
	EXPECT_NEAR(m.cov(0, 0), 0.01, 1e-15);
	EXPECT_NEAR(m.cov(1, 1), std::pow(0.5 * M_PI / 180, 2), 1e-15);
	EXPECT_EQ(m.cov(0, 1), 0);
}

TEST(NoiseCalibration, KeepsTheOtherNoiseComponentWhenOneIsSet)
{
	NoiseCalibration c;
	c.range_std_m = 0.1;
	const auto m = calibratedStep(stepWithOdometryAndScan(), c).scan->measurements[0];
	EXPECT_NEAR(m.cov(0, 0), 0.01, 1e-15);
	EXPECT_NEAR(m.cov(1, 1), 0.001, 1e-15);
}

TEST(NoiseCalibration, SetsTheSightingNoiseOnlyWhenGiven)
{
	NoiseCalibration c;
	c.range_std_m = 0.5;
	EXPECT_FALSE(calibratedStep(stepWithOdometryAndScan(), c).scan->sighting_cov);
	c.sighting_range_std_m = 0.2;
	const Scan scan = *calibratedStep(stepWithOdometryAndScan(), c).scan;
	const RangeBearing& m = scan.measurements[0];
	ASSERT_TRUE(scan.sighting_cov);
	EXPECT_NEAR((*scan.sighting_cov)(0, 0), 0.04, 1e-15);
	EXPECT_NEAR((*scan.sighting_cov)(1, 1), m.cov(1, 1), 1e-15);  // the bearing's as fused
	EXPECT_NEAR(m.cov(0, 0), 0.25, 1e-15);
	EXPECT_NEAR(sightingCov(scan, m)(0, 0), 0.04, 1e-15);
}

TEST(NoiseCalibration, ARangeBelowItsBiasStaysAtZero)
{
	NoiseCalibration c;
	c.range_bias_m = 0.05;
	StepInput step = stepWithOdometryAndScan();
	step.scan->measurements[0].range_m = 0.01;
	EXPECT_EQ(calibratedStep(step, c).scan->measurements[0].range_m, 0);
}

TEST(NoiseCalibration, FileRoundTrip)
{
	test::TempDir dir;
	NoiseCalibration c;
	c.odometry_std_scale_phi = 3.25;
	c.range_std_m = 0.1477;
	c.bearing_bias_deg = -0.111;
	c.sighting_bearing_std_deg = 0.686;
	const std::string path = dir.file("calibration.ini");
	writeTextAtomically(path, noiseCalibrationText(c, "fitted by hand\n\ntwo lines"));
	const std::string text = test::readText(path);
	EXPECT_EQ(text.rfind("# fitted by hand\n#\n# two lines\n", 0), 0u) << text;
	const NoiseCalibration back = loadNoiseCalibration(path);
	EXPECT_EQ(back.odometry_std_scale_phi, 3.25);
	EXPECT_EQ(back.range_std_m, 0.1477);
	EXPECT_EQ(back.bearing_bias_deg, -0.111);
	EXPECT_EQ(back.sighting_bearing_std_deg, 0.686);
	EXPECT_EQ(back.odometry_turn_scale, 1);
}

TEST(NoiseCalibration, BadFilesAreOneErrorNamingFileAndKey)
{
	test::TempDir dir;
	const auto refused = [&](const std::string& text, const std::string& phrase) {
		const std::string path = dir.file("c.ini");
		writeTextAtomically(path, text);
		try
		{
			loadNoiseCalibration(path);
			ADD_FAILURE() << "accepted: " << text;
		}
		catch (const ConfigError& e)
		{
			EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
			EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
		}
	};
	refused("[calibration]\nrange_std_m = -1\n", "range_std_m");
	refused("[calibration]\nodometry_std_scale_xy = 0\n", "odometry_std_scale_xy");
	refused("[calibration]\nrange_sigma = 1\n", "range_sigma");
	refused("[esif]\nplugin = EkfSlam\n", "[esif]");
	refused("", "no [calibration] section");
	refused("[calibration]\nbearing_bias_deg = nan\n", "bearing_bias_deg");
}
