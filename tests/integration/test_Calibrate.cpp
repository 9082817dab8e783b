/// esif calibrate end to end on the committed simulation (rawlogs/grid196,
/// whose noise is known: range 0.1 m, bearing 1 deg, the simulator's
/// odometry), and a config using the calibration file it writes.

#include <EsifTestSupport.h>
#include <esif/calibration/NoiseCalibration.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace esif;
using namespace esif::test;

namespace
{
const std::string kRawlog = sourcePath("rawlogs/grid196.rawlog");

void writeFile(const std::string& path, const std::string& text) { std::ofstream(path) << text; }
}  // namespace

TEST(Calibrate, FitsTheSimulationsKnownNoiseAndAConfigUsesIt)
{
	TempDir dir;
	const std::string calibration = dir.file("calibration.ini");
	const auto r = runEsif("calibrate -r " + quoted(kRawlog) + " -o " + quoted(calibration));
	ASSERT_EQ(r.exit_code, 0) << r.out;
	EXPECT_NE(r.out.find("odometry over windows of W steps"), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("systematic odometry errors: not kept"), std::string::npos) << r.out;
	// 14,032 measurements: a fitted sigma has a relative standard error of 0.6%.
	const NoiseCalibration c = loadNoiseCalibration(calibration);
	EXPECT_NEAR(c.range_std_m, 0.1, 0.003);
	EXPECT_NEAR(c.bearing_std_deg, 1.0, 0.03);

	writeFile(dir.file("ekf.ini"), "[esif]\nplugin = EkfSlam\ncalibration = calibration.ini\n");
	const auto run = runEsif("run -q --no-figures --config " + quoted(dir.file("ekf.ini")) + " --rawlog " +
							 quoted(kRawlog) + " --out " + quoted(dir.file("run")));
	ASSERT_EQ(run.exit_code, 0) << run.out;
	const std::string params = readText(dir.file("run/params.ini"));
	EXPECT_NE(params.find("calibration = " + calibration), std::string::npos) << params;
	EXPECT_NE(params.find("#   range_std_m = "), std::string::npos) << params;
}

TEST(Calibrate, BadCalibrationsAreOneErrorNamingTheKey)
{
	TempDir dir;
	writeFile(dir.file("calibration.ini"), "[calibration]\nrange_std_m = 0.1\n");
	const auto refused = [&](const std::string& esif_section, const std::string& phrase) {
		writeFile(dir.file("c.ini"), "[esif]\nplugin = EkfSlam\n" + esif_section);
		expectOneErrorLine(runEsif("run -q --config " + quoted(dir.file("c.ini")) + " --rawlog " + quoted(kRawlog) +
								   " --out " + quoted(dir.file("out"))),
						   phrase);
		EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
	};
	refused("calibration = missing.ini\n", "calibration");
	refused("calibration = calibration.ini\nsensor_std_range_m = 0.2\n", "sensor_std_range_m");
}

TEST(Calibrate, RefusesWhatItCannotFitOrMustNotWrite)
{
	TempDir dir;
	// A rawlog without ground truth beside it and no reference run.
	std::filesystem::copy_file(kRawlog, dir.file("alone.rawlog"));
	expectOneErrorLine(runEsif("calibrate -r " + quoted(dir.file("alone.rawlog")) + " -o " + quoted(dir.file("c.ini"))),
					   "ground truth not found");
	// The output must not be an input.
	expectOneErrorLine(runEsif("calibrate -r " + quoted(kRawlog) + " -o " + quoted(kRawlog)), "--out");
	expectOneErrorLine(runEsif("calibrate -r " + quoted(kRawlog) + " --fit wheels -o " + quoted(dir.file("c.ini"))),
					   "--fit 'wheels'");
	expectOneErrorLine(runEsif("calibrate -r " + quoted(kRawlog) + " -r " + quoted(kRawlog) + " --reference-run " +
							   quoted(dir.path()) + " -o " + quoted(dir.file("c.ini"))),
					   "one --reference-run per --rawlog");
	EXPECT_FALSE(std::filesystem::exists(dir.file("c.ini")));
}

TEST(Calibrate, ReplacesItsOwnFileButNeverOneItDidNotWrite)
{
	TempDir dir;
	const std::string out = dir.file("calibration.ini");
	const std::string command = "calibrate -r " + quoted(kRawlog) + " -o " + quoted(out);
	ASSERT_EQ(runEsif(command).exit_code, 0);
	EXPECT_EQ(runEsif(command).exit_code, 0) << "its own file is replaced";
	writeFile(dir.file("mine.ini"), "[calibration]\nrange_std_m = 0.3\n");
	expectOneErrorLine(runEsif("calibrate -r " + quoted(kRawlog) + " -o " + quoted(dir.file("mine.ini"))), "mine.ini");
	EXPECT_EQ(readText(dir.file("mine.ini")), "[calibration]\nrange_std_m = 0.3\n");
}
