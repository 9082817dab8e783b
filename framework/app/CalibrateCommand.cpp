#include "CommandLine.h"
#include "Commands.h"

#include <esif/calibration/Calibration.h>
#include <esif/core/Errors.h>

#include <iostream>

namespace esif::app
{
namespace
{
/// The inputs: one reference run or ground-truth prefix per rawlog, or none.
std::vector<CalibrationInput> inputsOf(
	const std::vector<std::string>& rawlogs, const std::vector<std::string>& references,
	const std::vector<std::string>& truths)
{
	if (!references.empty() && references.size() != rawlogs.size())
		throw ConfigError("esif calibrate: give one --reference-run per --rawlog, in the same order, or none");
	if (!truths.empty() && truths.size() != rawlogs.size())
		throw ConfigError("esif calibrate: give one --ground-truth per --rawlog, in the same order, or none");
	if (!references.empty() && !truths.empty())
		throw ConfigError("esif calibrate: give --reference-run or --ground-truth, not both");
	std::vector<CalibrationInput> inputs;
	for (std::size_t i = 0; i < rawlogs.size(); ++i)
	{
		CalibrationInput in{rawlogs[i], std::nullopt, std::nullopt};
		if (!references.empty()) in.reference_run = references[i];
		if (!truths.empty()) in.ground_truth_prefix = truths[i];
		inputs.push_back(in);
	}
	return inputs;
}

NoiseFitSettings settingsOf(const std::string& fit, double outlier_fraction, double horizon_quantile,
							std::optional<int> horizon_steps, int sensor_horizon)
{
	NoiseFitSettings s;
	s.odometry_bias = s.odometry = s.sensor_noise = s.sensor_bias = false;
	for (const auto& part : splitCommas(fit))
	{
		if (part == "odometry") s.odometry = true;
		else if (part == "odometry-bias") s.odometry_bias = true;
		else if (part == "noise") s.sensor_noise = true;
		else if (part == "bias") s.sensor_bias = true;
		else throw ConfigError("esif calibrate: --fit '" + part + "': expected odometry, odometry-bias, noise or bias");
	}
	if (!s.odometry_bias && !s.odometry && !s.sensor_noise && !s.sensor_bias) throw ConfigError("esif calibrate: --fit names nothing to fit");
	if (!(outlier_fraction >= 0 && outlier_fraction < 0.5))
		throw ConfigError("esif calibrate: --outlier-fraction must be in [0, 0.5)");
	s.likelihood.outlier_fraction = outlier_fraction;
	if (!(horizon_quantile > 0 && horizon_quantile <= 1))
		throw ConfigError("esif calibrate: --horizon-quantile must be in (0, 1]");
	s.horizon_quantile = horizon_quantile;
	if (horizon_steps)
	{
		if (*horizon_steps < 1 || *horizon_steps > 100000)
			throw ConfigError("esif calibrate: --horizon-steps must be in [1, 100000]");
		s.horizon_steps = static_cast<std::size_t>(*horizon_steps);
	}
	if (sensor_horizon < 1 || sensor_horizon > 100000)
		throw ConfigError("esif calibrate: --sensor-horizon must be in [1, 100000]");
	s.sensor_horizon = static_cast<std::size_t>(sensor_horizon);
	return s;
}
}  // namespace

int calibrateCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd(
		"Fits the noise model of one or more rawlogs (systematic odometry errors, odometry noise scales, "
		"range-bearing noise and bias) by maximum likelihood against a reference trajectory and map, with the "
		"odometry consistent over windows of up to a horizon of steps, checks it on an EKF's innovations, and "
		"writes a calibration file that configs use with [esif] calibration = FILE. The reference is the rawlog's landmark IDs with its ground "
		"truth (beside it, or --ground-truth), or a full-SLAM run folder of the rawlog (--reference-run: its "
		"associations.txt, trajectory.tum and landmarks.txt). Several rawlogs of one sensor are fitted jointly.",
		' ', ESIF_VERSION);
	TCLAP::MultiArg<std::string> rawlogs("r", "rawlog", "MRPT rawlog (repeat for a joint fit)", true, "FILE", cmd);
	TCLAP::MultiArg<std::string> references(
		"", "reference-run", "run folder of the rawlog's full-SLAM optimum (one per --rawlog)", false, "DIR", cmd);
	TCLAP::MultiArg<std::string> truths(
		"g", "ground-truth", "ground-truth prefix (PREFIX_ground_truth.txt; one per --rawlog)", false, "PREFIX", cmd);
	TCLAP::ValueArg<std::string> fit(
		"", "fit", "what to fit, comma-separated: odometry (noise), odometry-bias (systematic distance, turn and drift errors), noise (range-bearing), bias (range-bearing)",
		false, "odometry,odometry-bias,noise,bias", "LIST", cmd);
	TCLAP::ValueArg<double> outlier_fraction(
		"", "outlier-fraction", "prior probability of an outlier measurement (misread, false detection)", false, 0.01,
		"P", cmd);
	TCLAP::ValueArg<double> horizon_quantile(
		"", "horizon-quantile",
		"the odometry horizon is this quantile of the steps between two sightings of one landmark", false, 0.9, "Q",
		cmd);
	TCLAP::ValueArg<int> horizon_steps("", "horizon-steps", "the odometry horizon in steps (instead of the quantile)",
									   false, 0, "N", cmd);
	TCLAP::ValueArg<int> sensor_horizon(
		"", "sensor-horizon",
		"inflate the range-bearing noise until sums of up to N consecutive sightings of one landmark are consistent "
		"(1: independent measurements)",
		false, 1, "N", cmd);
	TCLAP::ValueArg<std::string> out("o", "out", "calibration file to write", true, "", "FILE", cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;

	CalibrationRequest request;
	request.inputs = inputsOf(rawlogs.getValue(), references.getValue(), truths.getValue());
	request.out_path = out.getValue();
	request.settings = settingsOf(fit.getValue(), outlier_fraction.getValue(), horizon_quantile.getValue(),
								  valueIfSet(horizon_steps), sensor_horizon.getValue());
	const auto report = calibrateNoise(request);
	std::cout << report.text << "\nesif calibrate: wrote " << request.out_path << "\n";
	return 0;
}

}  // namespace esif::app
