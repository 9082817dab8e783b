/// \file MapOutputs.cpp
/// writeMapOutputs(): the fixed set of map files of one run, in one folder.

#include <esif/core/Errors.h>
#include <esif/formats/MapWriter.h>
#include <esif/run/MapOutputs.h>

#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;

namespace esif
{
void addMapOutputJobs(OutputJobs& jobs, const RunRecord& run, const std::string& dir, const MapWriterOptions& options)
{
	// Checked before any file is written, so a bad option or folder leaves the
	// folder untouched rather than with half of the outputs.
	validateMapWriterOptions(options);
	std::error_code ec;
	if (!fs::is_directory(dir, ec))
		throw InputError(dir + ": output folder does not exist or is not a folder");

	const fs::path d(dir);
	jobs.add("landmarks_txt", [&run, d] { writeLandmarksTxt(run.final_estimate, (d / "landmarks.txt").string()); });
	jobs.add("trajectory_tum", [&run, d] { writeTrajectoryTum(run.trajectory, (d / "trajectory.tum").string()); });
	jobs.add("map_simplemap", [&run, d] { writeSimpleMap(run, (d / "map.simplemap").string()); });
	jobs.add("scene_3dscene", [&run, d, options] { writeScene(run, (d / "scene.3Dscene").string(), options); });
	jobs.addFigure("map_png", [&run, d, options] { writeMapImage(run, (d / "map.png").string(), options); });
	// A map too wide for CLandmarksMap's 0.2 m grid (a city; a landmark
	// diverged far away) has no landmarks.gz: MRPT's tools could not load
	// it. The run and its other outputs stand; landmarks.txt holds the map.
	if (const auto refusal = landmarksGzRefusal(run.final_estimate))
		std::cerr << "esif: warning: landmarks.gz not written: " << *refusal << "; landmarks.txt holds the map\n";
	else
		jobs.add("landmarks_gz", [&run, d] { writeLandmarksGz(run.final_estimate, (d / "landmarks.gz").string()); });
}

void writeMapOutputs(const RunRecord& run, const std::string& dir, const MapWriterOptions& options, PhaseTimes* times)
{
	OutputJobs jobs;
	addMapOutputJobs(jobs, run, dir, options);
	jobs.run(times);
}

}  // namespace esif
