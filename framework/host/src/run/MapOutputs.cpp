/// \file MapOutputs.cpp
/// writeMapOutputs(): the fixed set of map files of one run, in one folder.

#include <esif/core/Errors.h>
#include <esif/formats/MapWriter.h>
#include <esif/run/MapOutputs.h>

#include <filesystem>

namespace fs = std::filesystem;

namespace esif
{
void writeMapOutputs(const RunRecord& run, const std::string& dir, const MapWriterOptions& options, PhaseTimes* times)
{
	// Checked before any file is written, so a bad option or folder leaves the
	// folder untouched rather than with half of the outputs.
	validateMapWriterOptions(options);
	std::error_code ec;
	if (!fs::is_directory(dir, ec))
		throw InputError(dir + ": output folder does not exist or is not a folder");

	const fs::path d(dir);
	PhaseTimes untimed;
	PhaseTimes& t = times ? *times : untimed;
	t.time("landmarks_txt", [&] { writeLandmarksTxt(run.final_estimate, (d / "landmarks.txt").string()); });
	t.time("trajectory_tum", [&] { writeTrajectoryTum(run.trajectory, (d / "trajectory.tum").string()); });
	t.time("map_simplemap", [&] { writeSimpleMap(run, (d / "map.simplemap").string()); });
	t.time("scene_3dscene", [&] { writeScene(run, (d / "scene.3Dscene").string(), options); });
	t.time("map_png", [&] { writeMapImage(run, (d / "map.png").string(), options); });
	// Last: it is the one output that can be refused for a map too large
	// for CLandmarksMap, and the others should exist even then.
	t.time("landmarks_gz", [&] { writeLandmarksGz(run.final_estimate, (d / "landmarks.gz").string()); });
}

}  // namespace esif
