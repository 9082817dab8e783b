#include <esif/core/Errors.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/render/FigureWriter.h>
#include <esif/localmaps/LocalMapBuild.h>
#include <esif/localmaps/LocalMapCheck.h>
#include <esif/run/ProgressBar.h>
#include <esif/run/RunConfig.h>
#include <esif/safeio/AtomicFile.h>
#include <esif/safeio/RunFolder.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace esif
{
namespace
{
const std::vector<std::string> kCheckOutputFiles = {"local_maps_nees.csv", "fusion_nees.csv", "consistency.png",
	"consistency.svg"};

/// Another run as a reference: its landmarks by ID and its trajectory as the
/// path, one row per step (a row per step is what places the maps on it).
GroundTruth referenceRunAsTruth(const std::string& dir, std::size_t steps)
{
	return runAsGroundTruth(readReferenceRun(dir, steps));
}

/// The reference start pose of `map`: the pose its first step starts from,
/// or, with an odometry link (eq. 5.4), the pose that step's motion reaches.
Pose2 referenceStart(const LocalMap& map, const GroundTruth& truth)
{
	if (map.link) return truth.path.at(map.first_step);
	return map.first_step == 0 ? Pose2::Zero() : truth.path.at(map.first_step - 1);
}

std::vector<LocalMapConsistency> checkEachMap(const LocalMapFolder& folder, const GroundTruth& truth)
{
	std::vector<LocalMapConsistency> out;
	const std::map<LandmarkId, Eigen::Vector2d> none;
	for (const LocalMap& map : folder.maps)
	{
		if (map.last_step >= truth.path.size()) break;	// beyond the reference path
		out.push_back(localMapConsistency(
			map, referenceStart(map, truth), truth.path[map.last_step], folder.truth_landmarks.value_or(none)));
	}
	return out;
}

/// Fuses the maps one by one into a fresh plugin and tests its whole state
/// after each fusion; landmarks pair by the maps' feature IDs.
std::vector<FusionConsistency> checkEachFusion(
	const LocalMapFolder& folder, const GroundTruth& truth, FilterPlugin& plugin, LocalMapJoiner& joiner,
	bool progress_bar)
{
	StateReference reference = stateReferenceOf(truth);
	reference.landmarks = folder.truth_landmarks.value_or(std::map<LandmarkId, Eigen::Vector2d>{});
	std::vector<FusionConsistency> out;
	ProgressBar progress("fusions", progress_bar ? folder.maps.size() : 0);
	for (const LocalMap& map : folder.maps)
	{
		joiner.joinLocalMap(map);
		const auto state = plugin.stateInformation();
		if (!state) return {};
		if (const auto nees = stateNees(*state, reference, std::nullopt, "after fusing local map " + std::to_string(map.index)))
			out.push_back({map.index, *nees});
		progress.update(out.size());
	}
	progress.finish();
	return out;
}

std::string number(double v)
{
	char buf[32];
	std::snprintf(buf, sizeof(buf), "%.6g", v);
	return buf;
}

/// NEES / dof of each row and its band, as a chart panel.
template <class Row, class Nees>
LinePanel neesPanel(const std::string& label, const std::vector<Row>& rows, Nees nees_of)
{
	LinePanel p{label + " NEES / dof", {{label, {}, rows.size() > 60}}, {{"95% (chi-square, dof)", {}}}, true};
	for (const Row& r : rows)
	{
		const StateNees& n = nees_of(r);
		const double dof = static_cast<double>(n.dof);
		p.series[0].points.emplace_back(static_cast<double>(r.index), n.nees / dof);
		p.bands[0].points.push_back({static_cast<double>(r.index), n.lower95 / dof, n.upper95 / dof});
	}
	return p;
}

void writeOutputs(const LocalMapCheckResult& r, const std::string& dir, int image_size_px)
{
	const std::filesystem::path d(dir);
	writeTextAtomically((d / "local_maps_nees.csv").string(), localMapNeesCsv(r.maps));
	writeTextAtomically((d / "fusion_nees.csv").string(), fusionNeesCsv(r.fusions));
	LineChart chart{"Local maps and their fusion against " + r.reference, "local map k", {}, "Fig. 3.9, 3.15"};
	chart.panels.push_back(neesPanel("each local map", r.maps, [](const LocalMapConsistency& m) -> const StateNees& { return m.whole; }));
	if (!r.fusions.empty())
		chart.panels.push_back(neesPanel("state after fusing map k", r.fusions, [](const FusionConsistency& f) -> const StateNees& { return f.nees; }));
	writeLineChartImage(chart, (d / "consistency.png").string(), image_size_px);
}

LocalMapCheckResult checkInto(const LocalMapCheckRequest& request, const std::string& out_dir, PluginLoader& loader)
{
	LocalMapsOfRawlog built = buildLocalMapsOfRawlog(
		{request.config_path, request.rawlog_path, request.ground_truth_prefix, out_dir, request.progress_bar}, loader);
	LocalMapCheckResult result;
	GroundTruth reference;
	if (request.reference_run)
	{
		reference = referenceRunAsTruth(*request.reference_run, built.log.steps.size());
		result.reference = *request.reference_run;
	}
	else if (built.truth && !built.truth->path.empty())
	{
		reference = *built.truth;
		result.reference = "truth";
	}
	else
		throw ConfigError(request.rawlog_path +
						  ": no ground truth with a robot path beside it; give --ground-truth or --reference-run");

	LocalMapFolder folder;
	folder.maps = std::move(built.maps);
	attachLocalMapGroundTruth(folder, built.log, reference);	 // reference landmarks by the maps' feature IDs
	result.maps = checkEachMap(folder, reference);

	// The plugin that lent the builder its parameters has fused nothing yet.
	result.fusions =
		checkEachFusion(folder, reference, *built.plugin, *asLocalMapJoiner(*built.plugin), request.progress_bar);
	writeOutputs(result, out_dir, request.image_size_px);
	return result;
}
}  // namespace

std::string localMapNeesCsv(const std::vector<LocalMapConsistency>& maps)
{
	std::string out =
		"k,features,features_compared,nees,dof,lower95,upper95,inside,nees_per_dof,end_pose_nees,"
		"end_heading_error_deg,features_inside_fraction\n";
	for (const auto& m : maps)
		out += std::to_string(m.index) + "," + std::to_string(m.features) + "," + std::to_string(m.features_compared) +
			   "," + number(m.whole.nees) + "," + std::to_string(m.whole.dof) + "," + number(m.whole.lower95) + "," +
			   number(m.whole.upper95) + "," + (m.whole.consistent() ? "1" : "0") + "," +
			   number(m.whole.nees / static_cast<double>(m.whole.dof)) + "," + number(m.end_pose_nees) + "," +
			   number(m.end_heading_error_rad * 180 / M_PI) + "," +
			   (m.features_inside_fraction ? number(*m.features_inside_fraction) : std::string()) + "\n";
	return out;
}

std::string fusionNeesCsv(const std::vector<FusionConsistency>& fusions)
{
	std::string out = "k,nees,dof,lower95,upper95,inside,nees_per_dof,landmarks_compared,poses_compared\n";
	for (const auto& f : fusions)
		out += std::to_string(f.index) + "," + number(f.nees.nees) + "," + std::to_string(f.nees.dof) + "," +
			   number(f.nees.lower95) + "," + number(f.nees.upper95) + "," + (f.nees.consistent() ? "1" : "0") + "," +
			   number(f.nees.nees / static_cast<double>(f.nees.dof)) + "," + std::to_string(f.nees.landmarks_compared) +
			   "," + std::to_string(f.nees.poses_compared) + "\n";
	return out;
}

LocalMapCheckResult runLocalMapCheck(const LocalMapCheckRequest& request, PluginLoader& loader)
{
	auto inputs = rawlogRunInputs(request.config_path, request.rawlog_path, request.ground_truth_prefix, std::nullopt);
	inputs.push_back({"the reference run", request.reference_run.value_or("")});
	requireOutputApart(request.out_dir, inputs);
	return writeRunFolder(request.out_dir, kCheckOutputFiles, [&](const std::string& staging) {
		return checkInto(request, staging, loader);
	});
}

}  // namespace esif
