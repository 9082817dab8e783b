#pragma once
/// \file MapWriter.h
/// Writes the map outputs of a run, each atomically, into one folder:
/// map.simplemap, landmarks.gz, landmarks.txt, trajectory.tum, scene.3Dscene
/// and map.png.

#include <esif/io/RunRecord.h>

#include <string>

namespace esif
{
struct MapWriterOptions
{
	int image_size_px = 1000;	///< map.png width and height
	double ellipse_sigmas = 2.0;  ///< landmark ellipses drawn at this many sigmas
};

/// Writes all map outputs for `run` into `dir` (which must exist).
/// Throws ConfigError for invalid options (image_size_px outside [200,
/// 16384], ellipse_sigmas not finite and > 0) before writing anything, and
/// InputError naming the file when one cannot be written. landmarks.gz is
/// written last: MRPT's CLandmarksMap keeps a 0.2 m grid over the whole map,
/// so a map wider than about 630 m (e.g. a diverged landmark) is refused
/// there with an InputError after the other files are in place. Non-finite
/// landmarks are left out of landmarks.gz, the scene and the image, and
/// written as `nan` in landmarks.txt.
void writeMapOutputs(const RunRecord& run, const std::string& dir, const MapWriterOptions& options = {});

/// The individual writers, usable on their own.
void writeSimpleMap(const RunRecord& run, const std::string& path);
void writeLandmarksGz(const Estimate& estimate, const std::string& path);
void writeLandmarksTxt(const Estimate& estimate, const std::string& path);
void writeTrajectoryTum(const std::vector<TrajectoryPoint>& trajectory, const std::string& path);
void writeScene(const RunRecord& run, const std::string& path, const MapWriterOptions& options);
void writeMapImage(const RunRecord& run, const std::string& path, const MapWriterOptions& options);

}  // namespace esif
