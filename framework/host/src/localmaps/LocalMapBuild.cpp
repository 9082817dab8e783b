#include <esif/core/Errors.h>
#include <esif/eval/AssociationAudit.h>
#include <esif/formats/AssociationFile.h>
#include <esif/localmap/LocalMapBuilder.h>
#include <esif/localmaps/LocalMapBuild.h>
#include <esif/run/LandmarkIdRequirement.h>
#include <esif/run/ProgressBar.h>
#include <esif/run/RunConfig.h>
#include <esif/safeio/RunFolder.h>

#include <algorithm>
#include <iostream>

namespace esif
{
std::vector<LocalMap> buildLocalMaps(const Rawlog& log, const LocalMapBuilderParams& params, bool progress_bar)
{
	LocalMapBuilder builder(params);
	if (const auto largest = largestInputLandmarkId(log, nullptr)) builder.reserveIdsUpTo(*largest);
	std::vector<LocalMap> maps;
	ProgressBar progress("local maps", progress_bar ? log.steps.size() : 0);
	for (std::size_t k = 0; k < log.steps.size(); ++k)
	{
		try
		{
			builder.processStep(log.steps[k]);
		}
		catch (const NumericalError& e)
		{
			throw NumericalError(log.path + ": step " + std::to_string(k) + ": " + e.what());
		}
		if (auto map = builder.takeClosedMap()) maps.push_back(std::move(*map));
		progress.update(k + 1);
	}
	try
	{
		if (auto last = builder.finish()) maps.push_back(std::move(*last));
	}
	catch (const NumericalError& e)
	{
		throw NumericalError(log.path + ": end of log: " + e.what());
	}
	progress.finish();
	return maps;
}

LandmarkId makeFeatureIdsPositive(std::vector<LocalMap>& maps)
{
	LandmarkId smallest = 1;
	for (const LocalMap& map : maps)
		for (const auto& f : map.features) smallest = std::min(smallest, f.id);
	const LandmarkId offset = 1 - smallest;
	if (offset == 0) return 0;
	for (LocalMap& map : maps)
	{
		for (auto& f : map.features) f.id += offset;
		for (auto& report : map.step_reports)
			for (auto& a : report.associations)
				if (a.kind != Association::Kind::Rejected) a.id += offset;
	}
	return offset;
}

void attachLocalMapGroundTruth(LocalMapFolder& folder, const Rawlog& log, const GroundTruth& truth)
{
	AssociationAudit audit;
	for (const LocalMap& map : folder.maps)
		for (std::size_t i = 0; i < map.step_reports.size(); ++i)
			if (map.first_step + i < log.true_ids.size()) audit.record(map.step_reports[i], log.true_ids[map.first_step + i]);
	const auto feature_to_true = audit.filterToTrue();

	std::map<LandmarkId, Eigen::Vector2d> landmarks;
	for (const LocalMap& map : folder.maps)
		for (const auto& f : map.features)
			if (const auto t = feature_to_true.find(f.id); t != feature_to_true.end())
				if (const auto p = truth.landmarks.find(t->second); p != truth.landmarks.end())
					landmarks.emplace(f.id, p->second);
	std::map<std::size_t, Pose2> end_poses;
	for (const LocalMap& map : folder.maps)
		if (map.last_step < truth.path.size()) end_poses.emplace(map.index, truth.path[map.last_step]);
	folder.truth_landmarks = std::move(landmarks);
	if (!end_poses.empty()) folder.truth_end_poses = std::move(end_poses);
}

LocalMapsOfRawlog buildLocalMapsOfRawlog(const LocalMapBuildRequest& request, PluginLoader& loader)
{
	const ConfigFile cfg = ConfigFile::load(request.config_path);
	const HostParams host = loadHostParams(cfg);
	auto plugin = createConfiguredPlugin(cfg, host, loader);
	const LocalMapJoiner* joiner = asLocalMapJoiner(*plugin);
	if (!joiner) throw ConfigError(cfg.origin() + ": plugin " + host.plugin + " is not a local-map joining plugin");
	// Maps built apart from any global map cannot be associated with one.
	if (joiner->localMapBuilderParams().local_map_global_features_radius_m > 0)
		throw ConfigError(cfg.origin() + ": local_map_global_features_radius_m needs the joining filter's global map "
										 "while the maps are built; esif localmaps build writes maps without one: set it to 0");
	const auto associations = locateAssociations(cfg, host, false);

	Rawlog log = readRawlog(request.rawlog_path, readOptionsOf(host));
	if (log.truncation_warning) std::cerr << "esif: warning: " << *log.truncation_warning << "\n";
	applyNoiseCalibration(log.steps, host.noise);
	if (associations) applyAssociations(log, readAssociationFile(*associations, log.steps.size()), *associations);
	const auto truth = findGroundTruth(request.ground_truth_prefix, request.rawlog_path);

	LocalMapsOfRawlog out;
	out.maps = buildLocalMaps(log, joiner->localMapBuilderParams(), request.progress_bar);
	out.id_offset = makeFeatureIdsPositive(out.maps);
	if (truth) out.truth = truth->inInitialPoseFrame();
	out.log = std::move(log);
	out.plugin = std::move(plugin);
	return out;
}

namespace
{
/// The whole build, writing into `out_dir` (the partial folder).
LocalMapBuildResult buildInto(const LocalMapBuildRequest& request, const std::string& out_dir, PluginLoader& loader)
{
	LocalMapsOfRawlog built = buildLocalMapsOfRawlog(request, loader);
	LocalMapBuildResult out;
	out.folder.maps = std::move(built.maps);
	out.id_offset = built.id_offset;
	if (built.truth) attachLocalMapGroundTruth(out.folder, built.log, *built.truth);
	writeLocalMapFiles(out.folder, out_dir);
	return out;
}
}  // namespace

void writeLocalMapFolder(const LocalMapFolder& folder, const std::string& dir)
{
	writeRunFolder(dir, {"localmap_1.txt"}, [&](const std::string& staging) {
		writeLocalMapFiles(folder, staging);
		return 0;
	});
}

LocalMapBuildResult runLocalMapBuild(const LocalMapBuildRequest& request, PluginLoader& loader)
{
	requireOutputApart(
		request.out_dir,
		rawlogRunInputs(request.config_path, request.rawlog_path, request.ground_truth_prefix, std::nullopt));
	// Locked, written aside and swapped into place like a run's folder.
	return writeRunFolder(request.out_dir, {"localmap_1.txt"}, [&](const std::string& staging) {
		return buildInto(request, staging, loader);
	});
}

}  // namespace esif
