#include "RunFiles.h"

#include <esif/formats/AssociationFile.h>
#include <esif/render/FigureWriter.h>
#include <esif/run/MapOutputs.h>
#include <esif/run/RunConfig.h>
#include <esif/run/RunStats.h>
#include <esif/safeio/AtomicFile.h>

#include <filesystem>

namespace esif
{
void writeRunFiles(
	const std::string& dir, const HostParams& host, const FilterPlugin& plugin, const RunFilesInput& in,
	PhaseTimes& times, OutputJobs extra)
{
	MapWriterOptions map_options;
	map_options.image_size_px = host.image_size_px;
	OutputJobs jobs;
	addMapOutputJobs(jobs, in.record, dir, map_options);
	const auto d = std::filesystem::path(dir);
	// The pattern is taken here, on the calling thread: plugins are not
	// asked to be thread-safe.
	auto pattern = plugin.informationPattern();
	jobs.addFigure("info_matrix_png", [pattern = std::move(pattern), d, &host] {
		if (pattern) writeInformationPatternImage(*pattern, (d / "info_matrix.png").string(), host.image_size_px);
	});
	if (!in.fusion_costs.empty())
		jobs.addFigure("localmap_times_png", [&in, d, &host] {
			writeLocalMapTimesImage(in.fusion_costs, (d / "localmap_times.png").string(), host.image_size_px);
		});
	const std::string params_ini = effectiveParamsIni(host, plugin);
	jobs.add("params_ini", [params_ini, d] { writeTextAtomically((d / "params.ini").string(), params_ini); });
	jobs.add("associations_txt", [&in, d, &host] {
		writeAssociationFile((d / kAssociationFileName).string(), in.reports, host.plugin, in.input_path);
	});
	jobs.add("landmark_identities_txt", [&in, d] {
		writeLandmarkIdentityFile((d / kLandmarkIdentityFileName).string(), in.identities);
	});
	jobs.append(std::move(extra));
	if (!in.figures) jobs.dropFigures();
	jobs.run(&times);
}

void setRunIdentityStats(Stats& stats, const HostParams& host, const FilterPlugin& plugin, const std::string& config)
{
	stats.set("plugin", StatValue(host.plugin));
	stats.set("formulation", StatValue(std::string(formulationName(plugin.formulation()))));
	stats.set("label", StatValue(host.label));
	stats.set("config", StatValue(config));
}

void setRunOutcomeStats(
	Stats& stats, double finish_us, const CostFigures& cost, const AssociationAudit& audit, const MapScores& scores,
	const std::optional<Accuracy>& accuracy)
{
	stats.set("finish_us", StatValue(finish_us));
	stats.set("peak_rss_mb", StatValue(peakRssMb()));
	setCostStats(stats, cost);
	setAssociationStats(stats, audit);
	setAssociationScoreStats(stats, scores.association);
	setAccuracyStats(stats, accuracy);
	stats.set("landmark_ospa_m", scores.landmark_ospa_m);
	stats.set("ospa_c_m", scores.ospa_c_m);
}

void closeRunStats(Stats& stats, const std::optional<StateNees>& nees, const std::string& nees_reference,
				   const PhaseTimes& times, const std::string& dir)
{
	setStateNeesStats(stats, nees, nees_reference);
	times.setStats(stats);
	flagSuspectResult(stats);
	writeTextAtomically((std::filesystem::path(dir) / "stats.json").string(), stats.toJson());
}

}  // namespace esif
