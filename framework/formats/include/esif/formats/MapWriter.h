#pragma once
/// \file MapWriter.h
/// The map files of a run, each written atomically: map.simplemap,
/// landmarks.gz (MRPT formats) and landmarks.txt, trajectory.tum (text).
/// The figures beside them (map.png, scene.3Dscene) are drawn by
/// esif/render/MapRender.h; esif/run/MapOutputs.h writes the whole set.

#include <esif/formats/RunRecord.h>

#include <optional>
#include <string>

namespace esif
{
void writeSimpleMap(const RunRecord& run, const std::string& path);
/// MRPT's CLandmarksMap keeps a 0.2 m grid over the whole map, so a map wider
/// than about 630 m (a city, or a diverged landmark) is refused with an
/// InputError (landmarksGzRefusal says so beforehand). Non-finite landmarks
/// are left out.
void writeLandmarksGz(const Estimate& estimate, const std::string& path);
/// Why writeLandmarksGz would refuse `estimate` (its span), or nullopt.
std::optional<std::string> landmarksGzRefusal(const Estimate& estimate);
/// Non-finite landmarks are written as `nan`.
void writeLandmarksTxt(const Estimate& estimate, const std::string& path);
void writeTrajectoryTum(const std::vector<TrajectoryPoint>& trajectory, const std::string& path);

}  // namespace esif
