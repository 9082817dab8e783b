#include "CommandLine.h"
#include "Commands.h"

#include <esif/core/Errors.h>
#include <esif/interop/G2oExport.h>

#include <iostream>

namespace esif::app
{
int exportCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd(
		"Writes a rawlog's full-SLAM problem for other solvers. Formats: g2o (VERTEX_SE2 / VERTEX_XY / EDGE_SE2 "
		"and a landmark edge; pose i is vertex i, pose 0 the initial pose and fixed, landmark L is vertex "
		"P + L for P poses). `esif import g2o` reads a solution back into a run folder.",
		' ', ESIF_VERSION);
	TCLAP::UnlabeledValueArg<std::string> format("format", "output format: g2o", true, "", "FORMAT", cmd);
	TCLAP::ValueArg<std::string> rawlog("r", "rawlog", "MRPT rawlog (gz or plain)", true, "", "FILE", cmd);
	TCLAP::ValueArg<std::string> associations_from(
		"", "associations-from",
		"run folder of this rawlog: its associations.txt gives the landmark IDs (needed when the rawlog has "
		"none), its trajectory.tum and landmarks.txt the initial values (default: dead reckoning and first "
		"sightings)",
		false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> landmark_edge(
		"", "landmark-edge",
		"xy: EDGE_SE2_XY, the landmark in the robot frame with its propagated information (g2o); br: "
		"'BR pose landmark bearing range sigma_bearing sigma_range' (GTSAM readG2o, which ignores EDGE_SE2_XY)",
		false, "xy", "xy|br", cmd);
	TCLAP::ValueArg<std::string> out("o", "out", "g2o file to write", true, "", "FILE", cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;
	if (format.getValue() != "g2o")
		throw ConfigError("esif export: unknown format '" + format.getValue() + "' (known: g2o)");
	if (landmark_edge.getValue() != "xy" && landmark_edge.getValue() != "br")
		throw ConfigError("esif export: --landmark-edge '" + landmark_edge.getValue() + "': expected xy or br");

	G2oExportRequest request;
	request.rawlog_path = rawlog.getValue();
	if (associations_from.isSet()) request.run_dir = associations_from.getValue();
	request.out_path = out.getValue();
	request.landmark_edge = landmark_edge.getValue() == "xy" ? G2oLandmarkEdge::PointXY : G2oLandmarkEdge::BearingRange;
	const auto s = exportG2o(request);
	std::cout << "esif export: " << request.out_path << ": " << s.poses << " poses, " << s.landmarks << " landmarks, "
			  << s.odometry_edges << " odometry edges, " << s.landmark_edges << " landmark edges";
	if (s.measurements_without_id) std::cout << " (" << s.measurements_without_id << " measurements without ID left out)";
	std::cout << "\n";
	return 0;
}

}  // namespace esif::app
