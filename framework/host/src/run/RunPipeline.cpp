#include "RunFiles.h"

#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/eval/EstimationErrorFiles.h>
#include <esif/eval/Evaluator.h>
#include <esif/eval/LandmarkIdentities.h>
#include <esif/eval/MapOspa.h>
#include <esif/eval/RunDifference.h>
#include <esif/formats/AssociationFile.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/RawlogReader.h>
#include <esif/render/FigureWriter.h>
#include <esif/run/HostParams.h>
#include <esif/run/InitialRun.h>
#include <esif/run/LandmarkIdRequirement.h>
#include <esif/run/MemoryRequirement.h>
#include <esif/run/Replay.h>
#include <esif/run/RunPipeline.h>
#include <esif/run/RunConfig.h>
#include <esif/run/RunStats.h>
#include <esif/formats/MeasurementTruth.h>

#include <chrono>
#include <filesystem>
#include <iostream>

namespace esif
{
namespace
{
/// What every run writes, checked before the folder is put in place
/// (landmarks.gz too, unless the map is too wide for it: MapOutputs.cpp).
const std::vector<std::string> kRunOutputFiles = {
	"landmarks.txt", "trajectory.tum", "map.simplemap", "scene.3Dscene", "map.png", "map.svg",
	"step_times.png", "step_times.svg", "params.ini", kAssociationFileName, kLandmarkIdentityFileName,
	"stats.json"};

/// `files` but the figures (PNG and SVG).
std::vector<std::string> withoutFigures(const std::vector<std::string>& files)
{
	std::vector<std::string> kept;
	for (const std::string& f : files)
	{
		const std::string ext = std::filesystem::path(f).extension().string();
		if (ext != ".png" && ext != ".svg") kept.push_back(f);
	}
	return kept;
}

/// A simulated rawlog with misread IDs or clutter has its measurements'
/// true landmarks beside it (MeasurementTruth.h): data association is then
/// scored against those, not against the rawlog's own (partly wrong) IDs.
void scoreAgainstMeasurementTruth(Rawlog& log, const std::string& prefix)
{
	auto truth = loadMeasurementTruth(prefix, log.true_ids.size());
	if (!truth) return;
	const std::string file = measurementTruthFileOf(prefix);
	truth->resize(log.true_ids.size());
	for (std::size_t k = 0; k < truth->size(); ++k)
		if ((*truth)[k].size() != log.true_ids[k].size())
			throw InputError(file + ": step " + std::to_string(k) + " lists " + std::to_string((*truth)[k].size()) +
							 " measurements, the rawlog has " + std::to_string(log.true_ids[k].size()));
	log.true_ids = std::move(*truth);
}

Stats collectStats(
	const HostParams& host, const RunRequest& request, const Rawlog& log, const ReplayResult& result,
	const FilterPlugin& plugin, const MapScores& scores, const std::optional<Accuracy>& accuracy, double total_wall_s)
{
	Stats s;
	const auto cost = plugin.costFigures();
	setRunIdentityStats(s, host, plugin, request.config_path);
	s.set("rawlog", StatValue(request.rawlog_path));
	s.set("steps", StatValue(static_cast<long long>(log.stepCount())));
	s.set("measurements", StatValue(static_cast<long long>(log.measurement_count)));
	s.set("landmarks", StatValue(static_cast<long long>(result.record.final_estimate.landmarks.size())));
	s.set("wall_s", StatValue(result.wall_s));
	s.set("total_wall_s", StatValue(total_wall_s));
	setTimeStats(s, "step_us", result.step_us);
	setRunOutcomeStats(s, result.finish_us, cost, result.audit, scores, accuracy);
	s.set("truncated", StatValue(log.truncation_warning ? 1LL : 0LL));
	if (!result.fusion_costs.empty()) setLocalMapJoinStats(s, result.fusion_costs.size(), {}, result.fusion_costs);
	setPluginCounters(s, cost);
	return s;
}

/// How the replay shows its progress and prepares each step read: the noise
/// calibration, then a recorded run's associations (the order the steps
/// were changed in when they were all kept).
ReplayOptions replayOptionsOf(
	const HostParams& host, const RunRequest& request, const std::optional<RecordedAssociations>& recorded)
{
	ReplayOptions options(host.keyframe_min_distance_m, request.progress_bar);
	const bool calibrated = !host.noise.isIdentity();
	if (calibrated || recorded)
		options.prepare = [&host, &recorded, calibrated](StepInput& step) {
			if (calibrated) step = calibratedStep(step, host.noise);
			if (recorded) applyRecordedStep(step, recorded->steps[step.index]);
		};
	return options;
}

/// The whole run, writing into request.out_dir (the partial folder).
Stats runInto(const RunRequest& request, PluginLoader& loader)
{
	const auto t0 = std::chrono::steady_clock::now();
	PhaseTimes times;
	const ConfigFile cfg = ConfigFile::load(request.config_path);
	HostParams host = loadHostParams(cfg);
	if (request.associations_from) host.associations_from = *request.associations_from;	// params.ini shows the folder used
	auto plugin = createConfiguredPlugin(cfg, host, loader);
	const auto associations = locateAssociations(cfg, host, request.associations_from.has_value());
	auto initial_estimate = readInitialRun(cfg, host);

	RawlogReadOptions read_options = readOptionsOf(host);
	// The replay reads the steps again, one at a time (RawlogSteps.h): on a
	// long log they are most of what the run would hold.
	read_options.keep_steps = false;
	Rawlog log = times.time("read", [&] { return readRawlog(request.rawlog_path, read_options); });
	if (log.truncation_warning) std::cerr << "esif: warning: " << *log.truncation_warning << "\n";
	std::optional<RecordedAssociations> recorded;
	if (associations)
	{
		recorded = readAssociationFile(*associations, log.stepCount());
		checkAssociationsFit(log, *recorded, *associations);
		log.any_landmark_id = anyIdGiven(*recorded);
	}
	scoreAgainstMeasurementTruth(
		log, request.ground_truth_prefix.value_or(groundTruthPrefixFor(request.rawlog_path)));
	requireLandmarkIds(*plugin, log, {cfg.origin(), host.hide_landmark_ids, associations.value_or("")});
	if (const auto largest = largestInputLandmarkId(log, recorded ? &*recorded : nullptr))
		plugin->reserveLandmarkIds(*largest);
	requireMemory(*plugin, log, cfg.origin(), memoryBudget(), recorded ? &*recorded : nullptr);
	if (initial_estimate)
	{
		requireInitialRunCovers(cfg, *initial_estimate, log.stepCount());
		plugin->setInitialEstimate(std::move(*initial_estimate));
	}
	auto truth = findGroundTruth(request.ground_truth_prefix, request.rawlog_path);
	if (truth)
		if (const auto problem = groundTruthProblem(*truth, log.stepCount(), log.truncation_warning.has_value()))
		{
			std::cerr << "esif: warning: " << *problem << "; accuracy and consistency figures left null\n";
			truth.reset();
		}
	const auto reference_run =
		request.reference_run ? std::optional<RunOutputs>(readReferenceRun(*request.reference_run, log.stepCount()))
							  : std::nullopt;
	ReplayResult result = replay(*plugin, log, replayOptionsOf(host, request, recorded));
	const std::map<LandmarkId, LandmarkId> filter_to_true = result.audit.filterToTrue();
	const LandmarkIdentities identities = landmarkIdentities(result.audit, result.record.final_estimate.landmarks);
	MapScores scores{scoreAssociations(identities, result.audit), result.ospa_cutoff_m, std::nullopt};

	std::optional<Accuracy> accuracy;
	if (truth)
		times.time("evaluate", [&] {
		result.record.truth = truth->inInitialPoseFrame();
		const auto pose_errors = poseErrors(*result.record.truth, result.record.trajectory);
		const auto landmark_errors =
			landmarkErrors(*result.record.truth, result.record.final_estimate, filter_to_true);
		accuracy = summarizeErrors(pose_errors, landmark_errors);
		if (scores.ospa_c_m)
			scores.landmark_ospa_m = truthOspa(
				*result.record.truth, result.record.final_estimate, result.audit.trueLandmarks(), *scores.ospa_c_m);
		// Per step and per landmark, for campaigns over many runs (esif montecarlo).
		writeEstimationErrorFiles(request.out_dir, pose_errors, landmark_errors);
	});

	OutputJobs step_times;
	step_times.addFigure("step_times_png", [&] {
		writeStepTimesImage(
			result.step_us, result.landmark_counts,
			(std::filesystem::path(request.out_dir) / "step_times.png").string(), host.image_size_px);
	});
	writeRunFiles(
		request.out_dir, host, *plugin,
		{result.record, result.reports, result.fusion_costs, request.rawlog_path, identities, request.figures}, times,
		std::move(step_times));
	const double total_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	Stats stats = collectStats(host, request, log, result, *plugin, scores, accuracy, total_wall_s);
	// After total_wall_s, like the whole-state test: read back from the files
	// just written, the run is measured exactly as `esif compare` measures it.
	if (reference_run)
		times.time("evaluate", [&] {
			setDifferenceStats(stats, runDifference(readRunOutputs(request.out_dir), *reference_run, scores.ospa_c_m));
		});
	// After total_wall_s: the whole-state test is a figure about the result,
	// against the reference run when one is given, else the ground truth.
	std::optional<StateReference> nees_against;
	std::string nees_reference;
	if (reference_run)
	{
		nees_against = stateReferenceOf(*reference_run, log.stepCount());
		nees_reference = request.reference_run_name.value_or(*request.reference_run);
	}
	else if (result.record.truth)
	{
		nees_against = stateReferenceOf(*result.record.truth);
		nees_reference = "truth";
	}
	const auto nees = times.time("state_nees", [&]() -> std::optional<StateNees> {
		if (!nees_against) return std::nullopt;
		return finalStateNees(*plugin, *nees_against, filter_to_true, request.config_path);
	});
	closeRunStats(stats, nees, nees_reference, times, request.out_dir);
	return stats;
}
}  // namespace

Stats runPipeline(const RunRequest& request, PluginLoader& loader)
{
	auto inputs = rawlogRunInputs(
		request.config_path, request.rawlog_path, request.ground_truth_prefix, request.associations_from);
	inputs.push_back({"the reference run", request.reference_run.value_or("")});
	return runInStagedFolder(request, inputs, request.figures ? kRunOutputFiles : withoutFigures(kRunOutputFiles),
		[&](const RunRequest& staged) { return runInto(staged, loader); });
}

}  // namespace esif
