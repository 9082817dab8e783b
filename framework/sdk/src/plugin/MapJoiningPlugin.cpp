#include <esif/core/Errors.h>
#include "localmap/SettledReports.h"
#include <esif/models/Se2.h>
#include <esif/plugin/MapJoiningPlugin.h>
#include <esif/sparse/SparseInformationCore.h>

#include <set>
#include <stdexcept>

namespace esif
{
void MapJoiningPlugin::startBuilder(const LocalMapBuilderParams& params)
{
	builder_params_ = params;
	builder_ = std::make_unique<LocalMapBuilder>(params);
	builder_->countOwnFeaturesWith([this](const LandmarkEkf& open_map, const std::set<LandmarkId>& own_ids) {
		return ownFeaturesInGlobalMap(open_map, own_ids);
	});
}

void MapJoiningPlugin::reserveLandmarkIds(LandmarkId largest_input_id)
{
	requireBuilder();
	builder_->reserveIdsUpTo(largest_input_id);
}

void MapJoiningPlugin::requireBuilder() const
{
	if (!builder_) throw std::logic_error(filter_name_ + ": used before configure()");
}

const LocalMapBuilder& MapJoiningPlugin::builder() const
{
	requireBuilder();
	return *builder_;
}

void MapJoiningPlugin::appendLocalMapCounters(std::vector<std::pair<std::string, double>>& counters) const
{
	if (!builder_) return;
	builder_->rejections().appendCounters(counters, "local_");
	if (localFeaturesCarryGlobalIds())
		counters.emplace_back("local_features_started_from_global", static_cast<double>(builder_->earlierFeatureStarts()));
}

StepReport MapJoiningPlugin::processStep(const StepInput& step)
{
	requireBuilder();
	built_from_steps_ = true;
	if (step.scan)
		for (const auto& m : step.scan->measurements) saw_measurement_without_id_ |= !m.id.has_value();
	StepReport report = builder_->processStep(step);
	if (auto map = builder_->takeClosedMap())
	{
		local_poses_.push_back({map->end_pose, map->covariance->topLeftCorner<3, 3>()});
		++maps_given_;
		fuseLocalMap(*map);
		giveGlobalFeaturesToOpenMap();
	}
	else
		local_poses_.push_back(builder_->openMap().robotPose());
	return report;
}

void MapJoiningPlugin::giveGlobalFeaturesToOpenMap()
{
	const double radius_m = builder_params_.local_map_global_features_radius_m;
	if (radius_m <= 0) return;
	auto features = globalFeaturesNearOpenMapStart(radius_m);
	if (!features)
		throw InputError(filter_name_ + ": local_map_global_features_radius_m is not supported by this filter");
	builder_->setEarlierFeatures(std::move(*features));
}

void MapJoiningPlugin::joinLocalMap(const LocalMap& map)
{
	requireBuilder();
	if (map.index != maps_given_ + 1)
		throw InputError(filter_name_ + ": local map " + std::to_string(map.index) + " given after " +
						 std::to_string(maps_given_) + " maps (maps must come in order from 1)");
	checkGivenMap(map);
	++maps_given_;
	fuseLocalMap(map);
}

void MapJoiningPlugin::finish()
{
	requireBuilder();
	if (auto map = builder_->finish())
	{
		++maps_given_;
		fuseLocalMap(*map);
	}
	finishJoining();
}

std::optional<std::vector<StepReport>> MapJoiningPlugin::finalReports() const
{
	const std::vector<SettledFusion> fusions = settledFusions();
	if (fusions.empty() || fusions.front().step_reports.empty()) return std::nullopt;
	std::vector<StepReport> out;
	std::set<LandmarkId> started;
	for (const auto& f : fusions) appendSettledReports(f.step_reports, f.feature_ids, f.decisions, started, out);
	return out;
}

std::optional<InformationPattern> MapJoiningPlugin::informationPattern() const
{
	requireBuilder();
	return globalInformation().pattern();
}

}  // namespace esif
