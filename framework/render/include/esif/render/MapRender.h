#pragma once
/// \file MapRender.h
/// The two drawn views of a run's map: map.png (top view with 2-sigma
/// ellipses) and scene.3Dscene (MRPT's 3-D scene, for SceneViewer3D).

#include <esif/formats/RunRecord.h>

#include <string>

namespace esif
{
struct MapWriterOptions
{
	int image_size_px = 1000;	///< map.png width and height
	double ellipse_sigmas = 2.0;  ///< landmark ellipses drawn at this many sigmas
};

/// Throws ConfigError for image_size_px outside [200, 16384] or
/// ellipse_sigmas not finite and > 0.
void validateMapWriterOptions(const MapWriterOptions& options);

/// Non-finite landmarks are left out of both.
void writeScene(const RunRecord& run, const std::string& path, const MapWriterOptions& options);
void writeMapImage(const RunRecord& run, const std::string& path, const MapWriterOptions& options);

}  // namespace esif
