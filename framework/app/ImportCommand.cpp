#include "CommandLine.h"
#include "Commands.h"

#include <esif/core/Errors.h>
#include <esif/formats/MrclamImporter.h>
#include <esif/formats/VictoriaParkImporter.h>
#include <esif/run/RawlogOutput.h>

#include <iostream>
#include <memory>
#include <vector>

namespace esif::app
{
namespace
{
/// The range-bearing sensor options every dataset importer takes, with the
/// defaults of its options struct (keep_ids, std_range_m, std_bearing_deg,
/// max_range_m, fov_deg).
struct SensorArgs
{
	template <class Options>
	SensorArgs(TCLAP::CmdLine& cmd, const Options& d)
		: no_ids("", "no-ids", "drop the landmark IDs (the filter must associate itself)", cmd),
		  std_range("", "std-range-m", "range noise 1-sigma [m]", false, d.std_range_m, "M", cmd),
		  std_bearing("", "std-bearing-deg", "bearing noise 1-sigma [deg]", false, d.std_bearing_deg, "DEG", cmd),
		  max_range("", "max-range-m", "sensor range stored in the rawlog [m]", false, d.max_range_m, "M", cmd),
		  fov("", "fov-deg", "sensor field of view stored in the rawlog [deg]", false, d.fov_deg, "DEG", cmd)
	{
	}

	template <class Options>
	void applyTo(Options& o)
	{
		o.keep_ids = !no_ids.getValue();
		o.std_range_m = std_range.getValue();
		o.std_bearing_deg = std_bearing.getValue();
		o.max_range_m = max_range.getValue();
		o.fov_deg = fov.getValue();
	}

	TCLAP::SwitchArg no_ids;
	TCLAP::ValueArg<double> std_range, std_bearing, max_range, fov;
};

int importMrclamCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd(
		"Converts one robot of a UTIAS MRCLAM recording into an MRPT rawlog: one step per distinct time of a "
		"landmark measurement (barcodes translated through Barcodes.dat; measurements of robots and of unknown "
		"barcodes dropped), odometry integrated from the velocity commands between steps with a velocity-model "
		"covariance, and the Vicon ground truth of the landmarks and of the robot at every step written beside "
		"it (OUT without .rawlog + _ground_truth.txt / _ground_truth_robot_path.txt), in the frame of the robot's "
		"true first pose. Defaults measured on dataset 6 against the Vicon truth.",
		' ', ESIF_VERSION);
	TCLAP::ValueArg<std::string> dataset("d", "dataset", "recording folder (MRCLAM_DatasetN)", true, "", "DIR", cmd);
	TCLAP::ValueArg<int> robot("r", "robot", "robot 1-5", true, 1, "N", cmd);
	TCLAP::ValueArg<std::string> out("o", "out", "rawlog to write (gz)", true, "", "FILE", cmd);
	const MrclamImportOptions d;
	SensorArgs sensor(cmd, d);
	std::vector<std::unique_ptr<TCLAP::ValueArg<double>>> noise_args;
	for (const auto& p : velocityNoiseParameters())
		noise_args.push_back(std::make_unique<TCLAP::ValueArg<double>>(
			"", p.flag, p.help, false, p.get(d.odometry_noise), p.unit, cmd));
	if (!parseCommandLine(cmd, argc, argv)) return 0;

	MrclamImportOptions options;
	options.robot = robot.getValue();
	sensor.applyTo(options);
	for (std::size_t i = 0; i < noise_args.size(); ++i)
		velocityNoiseParameters()[i].set(options.odometry_noise, noise_args[i]->getValue());
	const auto s = writeRawlogOutput(
		out.getValue(), {{"the MRCLAM recording", dataset.getValue()}},
		[&](const std::string& rawlog) { return importMrclam(dataset.getValue(), rawlog, options); });
	std::cout << "esif import: " << out.getValue() << ": robot " << options.robot << ", " << s.steps << " steps over "
			  << static_cast<long>(s.duration_s) << " s (longest gap " << s.longest_gap_s << " s), " << s.measurements
			  << " measurements of " << s.landmarks << " landmarks" << (options.keep_ids ? "" : " (IDs dropped)") << "; "
			  << s.robot_measurements << " measurements of robots and " << s.unknown_barcodes
			  << " of unknown barcodes dropped; ground truth beside it\n";
	return 0;
}
}  // namespace

int importCommand(int argc, char** argv)
{
	// A g2o solution becomes a run folder, not a rawlog; MRCLAM has its own options.
	if (argc >= 2 && std::string(argv[1]) == "g2o")
	{
		std::string prog = "esif import g2o";
		argv[1] = prog.data();
		return importG2oCommand(argc - 1, argv + 1);
	}
	if (argc >= 2 && std::string(argv[1]) == "mrclam")
	{
		std::string prog = "esif import mrclam";
		argv[1] = prog.data();
		return importMrclamCommand(argc - 1, argv + 1);
	}
	TCLAP::CmdLine cmd("Converts a dataset into an MRPT rawlog. Datasets: victoria-park (`esif import mrclam --help`: one robot of a UTIAS MRCLAM recording; `esif import g2o --help`: a g2o solution into a run folder).", ' ', ESIF_VERSION);
	TCLAP::UnlabeledValueArg<std::string> dataset("dataset", "dataset format: victoria-park", true, "", "DATASET", cmd);
	TCLAP::ValueArg<std::string> in("i", "in", "dataset file (e.g. victoria_park.txt)", true, "", "FILE", cmd);
	TCLAP::ValueArg<std::string> out("o", "out", "rawlog to write (gz)", true, "", "FILE", cmd);
	const VictoriaParkImportOptions d;
	SensorArgs sensor(cmd, d);
	TCLAP::ValueArg<double> dt("", "dt-s", "nominal time between poses [s]", false, d.dt_s, "S", cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;
	if (dataset.getValue() != "victoria-park")
		throw ConfigError("esif import: unknown dataset '" + printableToken(dataset.getValue()) +
						  "' (known: victoria-park, mrclam, g2o)");

	VictoriaParkImportOptions options;
	sensor.applyTo(options);
	options.dt_s = dt.getValue();
	const auto s = writeRawlogOutput(
		out.getValue(), {{"the dataset", in.getValue()}},
		[&](const std::string& rawlog) { return importVictoriaPark(in.getValue(), rawlog, options); });
	std::cout << "esif import: " << out.getValue() << ": " << s.poses << " poses, " << s.measurements
			  << " measurements of " << s.landmark_ids << " landmarks" << (options.keep_ids ? "" : " (IDs dropped)")
			  << "\n";
	return 0;
}

}  // namespace esif::app
