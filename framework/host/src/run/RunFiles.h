#pragma once
/// \file RunFiles.h
/// What the two pipelines (RunPipeline.cpp on rawlogs, LocalMapRunPipeline.cpp
/// on local-map folders) share: the run's files beside stats.json, the
/// stats.json keys every run has, its closing (whole-state NEES, suspect
/// flag, stats.json), and the staged, all-or-nothing run folder.

#include <esif/eval/AssociationAudit.h>
#include <esif/eval/AssociationScore.h>
#include <esif/eval/Evaluator.h>
#include <esif/eval/StateNees.h>
#include <esif/formats/LandmarkIdentityFile.h>
#include <esif/formats/RunRecord.h>
#include <esif/formats/StatsJson.h>
#include <esif/plugin/FilterPlugin.h>
#include <esif/plugin/LocalMapJoiner.h>
#include <esif/run/HostParams.h>
#include <esif/run/OutputJobs.h>
#include <esif/run/PhaseTimes.h>
#include <esif/safeio/OutputApart.h>
#include <esif/safeio/RunFolder.h>

#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// What a replay produced, as the run's files need it.
struct RunFilesInput
{
	const RunRecord& record;
	const std::vector<StepReport>& reports;	 ///< one per step or per local map
	const std::vector<LocalMapFusionCost>& fusion_costs;  ///< empty but for map joining
	std::string input_path;	 ///< the rawlog or local-map folder, named in associations.txt
	const LandmarkIdentities& identities;  ///< the final map's, for landmark_identities.txt
	bool figures = true;  ///< false: no PNG or SVG is drawn (`esif run --no-figures`)
};

/// How the final map scores without positions (AssociationScore.h) and by
/// OSPA (MapOspa.h): null figures where the run has no measurement truth,
/// no cut-off (runs on local maps) or no ground truth.
struct MapScores
{
	std::optional<AssociationScore> association;
	std::optional<double> ospa_c_m;
	std::optional<double> landmark_ospa_m;	///< against the ground truth
};

/// Writes the map outputs (MapOutputs.h), info_matrix.png (information-form
/// plugins), localmap_times.png (map joining), params.ini, associations.txt,
/// landmark_identities.txt and the caller's `extra` files into `dir`, side
/// by side (OutputJobs.h), each file's time recorded in `times`.
void writeRunFiles(
	const std::string& dir, const HostParams& host, const FilterPlugin& plugin, const RunFilesInput& in,
	PhaseTimes& times, OutputJobs extra = {});

/// Sets plugin, formulation, label and config: the keys every stats.json starts with.
void setRunIdentityStats(Stats& stats, const HostParams& host, const FilterPlugin& plugin, const std::string& config);

/// Sets finish_us, peak_rss_mb, the cost, association, map-score and accuracy keys.
void setRunOutcomeStats(
	Stats& stats, double finish_us, const CostFigures& cost, const AssociationAudit& audit, const MapScores& scores,
	const std::optional<Accuracy>& accuracy);

/// Sets the whole-state NEES keys and the phase times, flags a suspect
/// result and writes `dir`/stats.json: the last file of a run.
void closeRunStats(Stats& stats, const std::optional<StateNees>& nees, const std::string& nees_reference,
				   const PhaseTimes& times, const std::string& dir);

/// Runs `run(staged)` with the request's out_dir replaced by a staging
/// folder, after checking that no input is inside --out, and swaps the
/// folder into place when every `required` file is there (RunFolder.h).
template <class Request, class Run>
auto runInStagedFolder(
	const Request& request, const std::vector<NamedInput>& inputs, const std::vector<std::string>& required, Run&& run)
{
	requireOutputApart(request.out_dir, inputs);
	return writeRunFolder(request.out_dir, required, [&](const std::string& staging) {
		Request staged = request;
		staged.out_dir = staging;
		return run(staged);
	});
}

}  // namespace esif
