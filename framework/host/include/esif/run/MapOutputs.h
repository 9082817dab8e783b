#pragma once
/// \file MapOutputs.h
/// The fixed set of map outputs of a run, in one folder: map.simplemap,
/// landmarks.gz, landmarks.txt, trajectory.tum (esif/formats/MapWriter.h),
/// scene.3Dscene and map.png (esif/render/MapRender.h).

#include <esif/formats/RunRecord.h>
#include <esif/render/MapRender.h>
#include <esif/run/PhaseTimes.h>

#include <string>

namespace esif
{
/// Writes all map outputs for `run` into `dir` (which must exist). Throws
/// ConfigError for invalid options before writing anything, and InputError
/// naming the file when one cannot be written. landmarks.gz is written last:
/// it is the one output refused for a map too wide for CLandmarksMap
/// (esif/formats/MapWriter.h), and the others should exist even then. With
/// `times`, each file's writing is recorded under its name (map_png, ...).
void writeMapOutputs(
	const RunRecord& run, const std::string& dir, const MapWriterOptions& options = {}, PhaseTimes* times = nullptr);

}  // namespace esif
