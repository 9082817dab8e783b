/// \file G2oExport.cpp
/// The rawlog, with a run's data association applied, built into a
/// full-SLAM problem and written as g2o text.

#include <esif/core/Errors.h>
#include <esif/formats/AssociationFile.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/interop/G2oExport.h>
#include <esif/run/RunConfig.h>
#include <esif/safeio/FileSet.h>

#include <filesystem>

namespace esif
{
namespace
{
G2oExportSummary exportInto(const G2oExportRequest& request, const std::string& out_path)
{
	Rawlog log = readRawlog(request.rawlog_path);
	std::optional<RunOutputs> initial;
	if (request.run_dir)
	{
		const std::string& dir = *request.run_dir;
		if (!std::filesystem::is_directory(dir)) throw InputError(dir + ": run folder not found");
		const std::string associations = (std::filesystem::path(dir) / kAssociationFileName).string();
		applyAssociations(log, readAssociationFile(associations, log.steps.size()), associations);
		initial = readReferenceRun(dir, log.steps.size());
	}
	const FullSlamProblem problem =
		buildFullSlamProblem(log, initial ? &*initial : nullptr, request.run_dir.value_or(""));
	if (problem.observations.empty() && problem.measurements_without_id > 0)
		throw InputError(
			request.rawlog_path + ": no measurement carries a landmark ID: give --associations-from a run folder "
								  "of this rawlog (its associations.txt gives the IDs)");
	writeG2oFile(out_path, problem, request.landmark_edge, request.rawlog_path);
	return {problem.poses.size(), problem.landmarks.size(), problem.odometry.size(), problem.observations.size(),
			problem.measurements_without_id};
}
}  // namespace

G2oExportSummary exportG2o(const G2oExportRequest& request)
{
	// A file set of its own kind, claimed before anything is read: it
	// replaces only a g2o file esif wrote, never an input.
	return writeFileSet(
		"a g2o file", {request.out_path},
		{{"the rawlog", request.rawlog_path}, {"the run folder", request.run_dir.value_or("")}},
		[&](const FileSet& set) { return exportInto(request, set.staging(request.out_path)); });
}

}  // namespace esif
