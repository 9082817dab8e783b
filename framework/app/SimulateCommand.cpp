/// \file SimulateCommand.cpp
/// `esif simulate`: generates a simulated rawlog and its ground truth from the
/// [simulation] section of an INI file.

#include "CommandLine.h"
#include "Commands.h"

#include <esif/config/ConfigFile.h>
#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/formats/GroundTruth.h>
#include <esif/run/RawlogOutput.h>
#include <esif/formats/MeasurementTruth.h>
#include <esif/sim/Scenario.h>
#include <esif/sim/Simulator.h>

#include <mrpt/core/format.h>

#include <chrono>
#include <iostream>
#include <string>

namespace esif::app
{
namespace
{
/// Scans that cannot locate the robot: a featureless stretch shows here.
void printGaps(const SimulationSummary& s, const Scenario& scenario)
{
	const double metres_per_scan = scenario.speed_mps * scenario.dt_s;
	std::cout << mrpt::format(
		"Scans without any measurement: %zu, longest run %zu (%.1f m); longest run below two measurements %zu "
		"(%.1f m).\n",
		s.scans_without_measurements, s.longest_run_without_measurements,
		s.longest_run_without_measurements * metres_per_scan, s.longest_run_below_two_measurements,
		s.longest_run_below_two_measurements * metres_per_scan);
}

/// How many measurements lie about their landmark, and where the truth is:
/// data-association audits that take the rawlog's IDs as the truth count a
/// misread measurement as wrong when a filter associates it correctly.
void printOutliers(const SimulationSummary& s, const Scenario& scenario, const std::string& prefix)
{
	const std::size_t true_returns = s.measurements - s.spurious_measurements;
	if (scenario.wrong_id_rate > 0)
		std::cout << mrpt::format(
			"Wrong IDs: %zu of %zu landmark measurements carry another landmark's ID (%.3f %%, wrong_id_rate %g).\n",
			s.wrong_id_measurements, true_returns, true_returns ? 100.0 * s.wrong_id_measurements / true_returns : 0.0,
			scenario.wrong_id_rate);
	if (scenario.spurious_rate > 0)
		std::cout << mrpt::format(
			"Clutter: %zu spurious returns (%.3f per scan, spurious_rate %g), IDs %lld and up (no landmark).\n",
			s.spurious_measurements, s.steps ? double(s.spurious_measurements) / s.steps : 0.0, scenario.spurious_rate,
			static_cast<long long>(scenario.clutterIdBase()));
	std::cout << mrpt::format("True landmark of every measurement in %s.\n", measurementTruthFileOf(prefix).c_str());
}
}  // namespace

int simulateCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd(
		"Simulates the book's range-bearing SLAM experiments: writes OUT (a gz-compressed MRPT rawlog) and "
		"OUT-without-.rawlog + _ground_truth.txt / _ground_truth_robot_path.txt.",
		' ', "");
	TCLAP::ValueArg<std::string> config_arg(
		"", "config", "INI file with a [simulation] section (e.g. configs/sim/grid196.ini)", true, "", "INI",
		cmd);
	TCLAP::ValueArg<std::string> out_arg(
		"", "out", "output rawlog (e.g. rawlogs/grid196.rawlog)", true, "", "RAWLOG", cmd);
	TCLAP::ValueArg<int> seed_arg("", "seed", "overrides [simulation] seed (path, layout and noise)", false, 0, "N", cmd);
	TCLAP::ValueArg<int> noise_seed_arg(
		"", "noise-seed", "overrides [simulation] noise_seed: new noise on the same path and world", false, 0, "N",
		cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;

	ConfigFile config = ConfigFile::load(config_arg.getValue());
	Scenario::checkSections(config);  // before the overrides below add [simulation]
	// Through the INI so the seed is validated like any other value.
	if (seed_arg.isSet()) config.set("simulation", "seed", std::to_string(seed_arg.getValue()));
	if (noise_seed_arg.isSet()) config.set("simulation", "noise_seed", std::to_string(noise_seed_arg.getValue()));
	const Scenario scenario = Scenario::fromConfig(config);

	try
	{
		scenario.validate();
	}
	catch (const ConfigError& e)
	{
		// Rules across keys know no file: name it, like the per-key errors do.
		throw ConfigError(config_arg.getValue() + ": " + e.what());
	}

	// The rawlog and the ground-truth files beside it, one set: none may be
	// the scenario, none replaces a file esif did not write.
	const std::string prefix = groundTruthPrefixFor(out_arg.getValue());
	const auto start = std::chrono::steady_clock::now();
	const Simulator simulator(scenario);
	const SimulationSummary s = writeRawlogOutput(
		out_arg.getValue(), {{"the scenario", config_arg.getValue()}},
		[&](const std::string& rawlog) { return simulator.writeRawlog(rawlog); });
	const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

	std::cout << mrpt::format(
		"Simulated %s (seed %d, noise seed %u) in %.1f s: %zu steps, %zu measurements, %zu of %zu features seen, "
		"%.2f measurements per scan on average, true path length %.1f m. Ground truth in %s_ground_truth.txt "
		"and %s_ground_truth_robot_path.txt.\n",
		out_arg.getValue().c_str(), scenario.seed, scenario.effectiveNoiseSeed(), seconds, s.steps, s.measurements, s.features_seen, s.features,
		s.meanMeasurementsPerScan(), s.path_length_m, prefix.c_str(), prefix.c_str());
	printGaps(s, scenario);
	if (scenario.hasOutliers()) printOutliers(s, scenario, prefix);
	return 0;
}

}  // namespace esif::app
