/// esif calibrate's fit on the committed simulation (rawlogs/grid196, with
/// its ground truth): the simulator's noise is known, so a noise model
/// declared wrong on purpose, or odometry and sensor given systematic
/// errors on purpose, must be fitted back to the truth.
///
/// Tolerances: 14,032 measurements and 3,000 odometry steps. The relative
/// standard error of a fitted standard deviation from N samples is
/// 1/sqrt(2N): 0.6% for the sensor, 1.3% for one-step odometry; the
/// odometry scales are the largest over window lengths up to the horizon
/// (NoiseFit.h), each from at least 20 windows (at most 16%, and the
/// largest of several such estimates lies above the truth). So: sensor
/// noise to 3%, odometry scales to 20%, biases to 3 standard errors.

#include <EsifTestSupport.h>
#include <esif/calibration/CalibrationChecks.h>
#include <esif/calibration/NoiseFit.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/RawlogReader.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace esif;

namespace
{
/// grid196 with its true path and landmarks, every measurement keeping its ID.
ReferencedLog grid196()
{
	const std::string rawlog = test::sourcePath("rawlogs/grid196.rawlog");
	Rawlog log = readRawlog(rawlog);
	const GroundTruth truth = loadGroundTruth(groundTruthPrefixFor(rawlog))->inInitialPoseFrame();
	ReferencedLog out;
	out.log = {rawlog, std::move(log.steps)};
	out.path = truth.path;
	out.landmarks = truth.landmarks;
	return out;
}

/// The log as a sensor and odometry with `distortion` would have recorded it:
/// calibratedStep applies a calibration, so its inverse is applied here.
ReferencedLog distorted(ReferencedLog ref, const NoiseCalibration& distortion)
{
	applyNoiseCalibration(ref.log.steps, distortion);
	return ref;
}

/// Gives each landmark of `ref` a range error of its own, drawn once with
/// standard deviation `sigma` [m] (seed 3), added to every measurement of it:
/// an error that repeats over the sightings of one landmark.
void addLandmarkRangeErrors(ReferencedLog& ref, double sigma)
{
	std::mt19937 rng(3);
	std::normal_distribution<double> own(0, sigma);
	std::map<LandmarkId, double> error_of;
	for (const auto& [id, p] : ref.landmarks) error_of[id] = own(rng);
	for (auto& step : ref.log.steps)
		if (step.scan)
			for (auto& m : step.scan->measurements)
				if (m.id) m.range_m += error_of[*m.id];
}

NoiseFitResult fit(const ReferencedLog& ref, NoiseFitSettings settings = {})
{
	settings.horizon_steps = 200;  // grid196 closes loops over hundreds of steps
	return fitNoise({ref}, rawlogNoise({ref}), settings);
}
}  // namespace

TEST(NoiseFit, TheSimulatorsOwnNoiseIsFittedBack)
{
	const auto r = fit(grid196());
	EXPECT_NEAR(r.fitted.range_std_m, 0.1, 0.003);
	EXPECT_NEAR(r.fitted.bearing_std_deg, 1.0, 0.03);
	EXPECT_NEAR(r.fitted.odometry_std_scale_xy, 1.0, 0.2);
	EXPECT_NEAR(r.fitted.odometry_std_scale_phi, 1.0, 0.2);
	// Bias: 3 standard errors of a mean of 14,032 residuals.
	EXPECT_NEAR(r.fitted.range_bias_m, 0, 3 * 0.1 / std::sqrt(14032.0));
	EXPECT_NEAR(r.fitted.bearing_bias_deg, 0, 3 * 1.0 / std::sqrt(14032.0));
	// White odometry without systematic errors: nothing for the held-out test to keep.
	EXPECT_FALSE(r.odometry_bias_held_out);
	EXPECT_EQ(r.fitted.odometry_turn_scale, 1);
	// The innovations of the fitted model are as consistent as the truth's:
	// mean NIS 2 to 3%, and the 0.9999 gate passed by all but a few.
	EXPECT_NEAR(r.after.nis_mean, 2.0, 0.06);
	EXPECT_LT(r.after.above_gate_9999, 0.001);
}

TEST(NoiseFit, ANoiseDeclaredWrongIsCorrected)
{
	// The rawlog claims range 0.3 m, bearing 3 deg and half the odometry noise.
	NoiseCalibration wrong;
	wrong.range_std_m = 0.3;
	wrong.bearing_std_deg = 3;
	wrong.odometry_std_scale_xy = wrong.odometry_std_scale_phi = 0.5;
	const auto r = fit(distorted(grid196(), wrong));
	EXPECT_NEAR(r.fitted.range_std_m, 0.1, 0.003);
	EXPECT_NEAR(r.fitted.bearing_std_deg, 1.0, 0.03);
	EXPECT_NEAR(r.fitted.odometry_std_scale_xy, 2.0, 0.4);
	EXPECT_NEAR(r.fitted.odometry_std_scale_phi, 2.0, 0.4);
}

TEST(NoiseFit, SystematicErrorsAreFoundAndTakenOut)
{
	// A sensor reading 0.2 m long and 2 deg left, odometry under-reporting
	// turns by 5% and drifting 0.3 deg per metre.
	NoiseCalibration bias;
	bias.range_bias_m = -0.2;  // calibratedStep subtracts it: the log gains +0.2 m
	bias.bearing_bias_deg = -2;
	bias.odometry_turn_scale = 1 / 1.05;
	bias.odometry_heading_drift_deg_per_m = -0.3 / 1.05;
	const auto r = fit(distorted(grid196(), bias));
	EXPECT_NEAR(r.fitted.range_bias_m, 0.2, 3 * 0.1 / std::sqrt(14032.0));
	EXPECT_NEAR(r.fitted.bearing_bias_deg, 2, 3 * 1.0 / std::sqrt(14032.0));
	EXPECT_TRUE(r.odometry_bias_held_out);
	// The turn of a 200-step window is known to its heading noise, 0.3 deg
	// per step (the simulator's 3 deg/s at 10 Hz) over sqrt(200) steps, some
	// 4 deg, against windows that turn tens of degrees: 2% on the scale.
	EXPECT_NEAR(r.fitted.odometry_turn_scale, 1.05, 0.02);
	EXPECT_NEAR(r.fitted.odometry_heading_drift_deg_per_m, 0.3, 0.06);
	EXPECT_NEAR(r.fitted.odometry_std_scale_phi, 1.0, 0.2);
}

TEST(NoiseFit, HorizonIsTheQuantileOfTheGapsBetweenSightings)
{
	ReferencedLog ref;
	ref.log.steps.resize(30);
	// Landmark 1 seen at steps 0, 1, 2 and 20; landmark 2 at 5 and 6: gaps 1, 1, 18, 1.
	for (std::size_t k : {0, 1, 2, 20, 5, 6})
	{
		auto& step = ref.log.steps[k];
		if (!step.scan) step.scan = Scan{};
		RangeBearing m;
		m.id = (k == 5 || k == 6) ? 2 : 1;
		step.scan->measurements.push_back(m);
	}
	EXPECT_EQ(reobservationHorizon({ref}, 0.5), 1u);
	EXPECT_EQ(reobservationHorizon({ref}, 1.0), 18u);
}

TEST(SensorWindowCheck, IndependentErrorsStayFlatAndALandmarksOwnErrorGrows)
{
	ReferencedLog ref = grid196();
	auto white = sensorWindowChecks(ref.log.steps, ref.path, ref.landmarks, {1, 16});
	ASSERT_EQ(white.size(), 2u);
	// Independent errors: 1 at every W, to the spread of a chi-square mean
	// over hundreds of windows (about 10% at W = 16).
	EXPECT_NEAR(white[0].range_normalised, 1.0, 0.05);
	EXPECT_NEAR(white[1].range_normalised, 1.0, 0.2);
	// Each landmark given a range error of its own of 1 sigma: the sum over
	// W sightings grows as W + W^2 / W... normalised, 1 + W.
	addLandmarkRangeErrors(ref, 0.1);
	auto correlated = sensorWindowChecks(ref.log.steps, ref.path, ref.landmarks, {1, 16});
	EXPECT_NEAR(correlated[0].range_normalised, 2.0, 0.3);
	EXPECT_GT(correlated[1].range_normalised, 8.0);	 // 17 expected; a draw of 196 landmark errors spreads it
}

TEST(NoiseFit, ASensorHorizonInflatesTheFusedNoiseAndKeepsOneSightingsForAssociation)
{
	// Each landmark given a range error of its own of 0.1 m (as in the window
	// check above): one sighting's range error is then 0.14 m, a sum of 16
	// sightings of one landmark errs by far more than 16 independent ones.
	ReferencedLog ref = grid196();
	addLandmarkRangeErrors(ref, 0.1);
	NoiseFitSettings horizon16;
	horizon16.sensor_horizon = 16;
	const auto one = fit(ref), inflated = fit(ref, horizon16);
	EXPECT_EQ(one.fitted.sighting_range_std_m, 0);	// no horizon: one noise for both
	// The sighting noise is the fit of one measurement, to the spread of 196
	// landmark errors (a variance from 196 draws: 10%, 5% on the sigma).
	EXPECT_EQ(inflated.fitted.sighting_range_std_m, one.fitted.range_std_m);
	EXPECT_EQ(inflated.fitted.sighting_bearing_std_deg, one.fitted.bearing_std_deg);
	EXPECT_NEAR(one.fitted.range_std_m, std::hypot(0.1, 0.1), 0.1 * std::hypot(0.1, 0.1));
	// Fused: inflated toward sqrt(1 + 16 / 2) = 3x (own error half the variance).
	EXPECT_GT(inflated.fitted.range_std_m, 2 * inflated.fitted.sighting_range_std_m);
}
