#pragma once
/// \file MapOutputs.h
/// The fixed set of map outputs of a run, in one folder: map.simplemap,
/// landmarks.gz, landmarks.txt, trajectory.tum (esif/formats/MapWriter.h),
/// scene.3Dscene and map.png (esif/render/MapRender.h).

#include <esif/formats/RunRecord.h>
#include <esif/render/MapRender.h>
#include <esif/run/OutputJobs.h>
#include <esif/run/PhaseTimes.h>

#include <string>

namespace esif
{
/// Adds the writing of every map output for `run` into `dir` (which must
/// exist) to `jobs`, one job per file (phases landmarks_txt, ..., map_png,
/// landmarks_gz). Throws ConfigError for invalid options and InputError for
/// a missing folder before adding anything. `run` must outlive the jobs.
void addMapOutputJobs(OutputJobs& jobs, const RunRecord& run, const std::string& dir, const MapWriterOptions& options);

/// Writes all map outputs for `run` into `dir` (which must exist), side by
/// side (OutputJobs.h). Throws ConfigError for invalid options before
/// writing anything, and InputError naming the file when one cannot be
/// written; the others are written even then (landmarks.gz, refused for a
/// map too wide for CLandmarksMap, esif/formats/MapWriter.h, is the usual
/// case). With `times`, each file's writing is recorded under its name
/// (map_png, ...).
void writeMapOutputs(
	const RunRecord& run, const std::string& dir, const MapWriterOptions& options = {}, PhaseTimes* times = nullptr);

}  // namespace esif
