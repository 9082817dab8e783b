#include "CalibrationReportText.h"

#include <esif/calibration/Calibration.h>
#include <esif/core/Errors.h>
#include <esif/formats/AssociationFile.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/RawlogReader.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/safeio/AtomicFile.h>
#include <esif/safeio/FileSet.h>
#include <esif/formats/MeasurementTruth.h>

#include <filesystem>

namespace esif
{
namespace
{
/// A rawlog with every measurement's landmark set from the reference
/// association, and the reference's path and map when it has them.
struct PreparedInput
{
	ReferencedLog log;
	std::string reference_name;
};

void setIds(Rawlog& log, const std::vector<std::vector<std::optional<LandmarkId>>>& ids)
{
	for (std::size_t k = 0; k < log.steps.size() && k < ids.size(); ++k)
		if (log.steps[k].scan)
			for (std::size_t i = 0; i < log.steps[k].scan->measurements.size() && i < ids[k].size(); ++i)
				log.steps[k].scan->measurements[i].id = ids[k][i];
}

PreparedInput prepare(const CalibrationInput& input)
{
	PreparedInput out;
	std::optional<GroundTruth> reference;
	Rawlog log = readRawlog(input.rawlog);
	if (input.reference_run)
	{
		const std::string& dir = *input.reference_run;
		if (!std::filesystem::is_directory(dir)) throw InputError(dir + ": reference run folder not found");
		const std::string associations = (std::filesystem::path(dir) / "associations.txt").string();
		applyAssociations(log, readAssociationFile(associations, log.steps.size()), associations);
		reference = runAsGroundTruth(readReferenceRun(dir, log.steps.size()));
		out.reference_name = dir;
		out.log.fitted_reference = true;
	}
	else
	{
		const std::string prefix = input.ground_truth_prefix.value_or(groundTruthPrefixFor(input.rawlog));
		// A simulation with misread IDs or clutter: the measurements' true landmarks.
		if (const auto truth = loadMeasurementTruth(prefix, log.steps.size())) setIds(log, *truth);
		reference = loadGroundTruth(prefix);
		if (!reference) throw InputError(prefix + "_ground_truth.txt: ground truth not found (or give --reference-run)");
		reference = reference->inInitialPoseFrame();
		out.reference_name = prefix + "_ground_truth*.txt";
	}
	if (const auto problem = groundTruthProblem(*reference, log.steps.size(), log.truncation_warning.has_value()))
		throw InputError(out.reference_name + ": " + *problem);
	out.log.log = {input.rawlog, std::move(log.steps)};
	out.log.path = std::move(reference->path);
	out.log.landmarks = std::move(reference->landmarks);
	return out;
}

CalibrationInputChecks checksOf(
	const PreparedInput& in, const NoiseCalibration& before, const NoiseCalibration& after,
	const CalibrationRequest& request)
{
	CalibrationInputChecks c;
	c.rawlog = in.log.log.name;
	c.reference = in.reference_name;
	for (const auto* cal : {&before, &after})
	{
		auto steps = in.log.log.steps;
		applyNoiseCalibration(steps, *cal);
		const bool first = cal == &before;
		(first ? c.odometry_before : c.odometry_after) = odometryWindowChecks(steps, in.log.path, request.window_lengths);
		(first ? c.sensor_before : c.sensor_after) = sensorResidualCheck(steps, in.log.path, in.log.landmarks);
		(first ? c.sensor_windows_before : c.sensor_windows_after) =
			sensorWindowChecks(steps, in.log.path, in.log.landmarks, request.sensor_window_lengths);
	}
	return c;
}

std::vector<NamedInput> inputsOf(const CalibrationRequest& request)
{
	std::vector<NamedInput> inputs;
	for (const auto& in : request.inputs)
	{
		inputs.push_back({"a rawlog", in.rawlog});
		if (in.reference_run) inputs.push_back({"a reference run", *in.reference_run});
		const std::string prefix = in.ground_truth_prefix.value_or(groundTruthPrefixFor(in.rawlog));
		for (const auto& file : groundTruthFilesOf(prefix)) inputs.push_back({"a ground truth", file});
	}
	return inputs;
}
}  // namespace

CalibrationReport calibrateNoise(const CalibrationRequest& request)
{
	if (request.inputs.empty()) throw ConfigError("esif calibrate: no rawlog to calibrate");
	// A file set of its own kind, claimed before anything is read: it
	// replaces only a calibration file esif wrote, never an input (FileSet.h).
	return writeFileSet("a calibration file", {request.out_path}, inputsOf(request), [&](const FileSet& set) {
		std::vector<PreparedInput> prepared;
		std::vector<ReferencedLog> logs;
		for (const auto& input : request.inputs)
		{
			prepared.push_back(prepare(input));
			logs.push_back(prepared.back().log);
		}
		CalibrationReport report;
		report.fit = fitNoise(logs, rawlogNoise(logs), request.settings);
		for (const auto& in : prepared)
			report.checks.push_back(checksOf(in, report.fit.start, report.fit.fitted, request));
		report.text = calibrationReportText(report, request.settings);
		writeTextAtomically(set.staging(request.out_path), noiseCalibrationText(report.fit.fitted, report.text));
		return report;
	});
}

}  // namespace esif
