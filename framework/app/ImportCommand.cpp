#include "CommandLine.h"
#include "Commands.h"

#include <esif/core/Errors.h>
#include <esif/io/VictoriaParkImporter.h>

#include <iostream>

namespace esif::app
{
int importCommand(int argc, char** argv)
{
	// A g2o solution becomes a run folder, not a rawlog: its own options.
	if (argc >= 2 && std::string(argv[1]) == "g2o")
	{
		std::string prog = "esif import g2o";
		argv[1] = prog.data();
		return importG2oCommand(argc - 1, argv + 1);
	}
	TCLAP::CmdLine cmd("Converts a dataset into an MRPT rawlog. Datasets: victoria-park. (`esif import g2o --help`: a g2o solution into a run folder.)", ' ', ESIF_VERSION);
	TCLAP::UnlabeledValueArg<std::string> dataset("dataset", "dataset format: victoria-park", true, "", "DATASET", cmd);
	TCLAP::ValueArg<std::string> in("i", "in", "dataset file (e.g. victoria_park.txt)", true, "", "FILE", cmd);
	TCLAP::ValueArg<std::string> out("o", "out", "rawlog to write (gz)", true, "", "FILE", cmd);
	TCLAP::SwitchArg no_ids("", "no-ids", "drop the landmark IDs (the filter must associate itself)", cmd);
	const VictoriaParkImportOptions d;
	TCLAP::ValueArg<double> std_range("", "std-range-m", "range noise 1-sigma [m]", false, d.std_range_m, "M", cmd);
	TCLAP::ValueArg<double> std_bearing("", "std-bearing-deg", "bearing noise 1-sigma [deg]", false, d.std_bearing_deg,
										"DEG", cmd);
	TCLAP::ValueArg<double> max_range("", "max-range-m", "sensor range stored in the rawlog [m]", false, d.max_range_m,
									  "M", cmd);
	TCLAP::ValueArg<double> fov("", "fov-deg", "sensor field of view stored in the rawlog [deg]", false, d.fov_deg,
								"DEG", cmd);
	TCLAP::ValueArg<double> dt("", "dt-s", "nominal time between poses [s]", false, d.dt_s, "S", cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;
	if (dataset.getValue() != "victoria-park")
		throw ConfigError("esif import: unknown dataset '" + dataset.getValue() + "' (known: victoria-park)");

	VictoriaParkImportOptions options;
	options.keep_ids = !no_ids.getValue();
	options.std_range_m = std_range.getValue();
	options.std_bearing_deg = std_bearing.getValue();
	options.max_range_m = max_range.getValue();
	options.fov_deg = fov.getValue();
	options.dt_s = dt.getValue();
	const auto s = importVictoriaPark(in.getValue(), out.getValue(), options);
	std::cout << "esif import: " << out.getValue() << ": " << s.poses << " poses, " << s.measurements
			  << " measurements of " << s.landmark_ids << " landmarks" << (options.keep_ids ? "" : " (IDs dropped)")
			  << "\n";
	return 0;
}

}  // namespace esif::app
