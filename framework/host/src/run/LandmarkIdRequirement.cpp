#include <esif/core/Errors.h>
#include <esif/loader/PluginName.h>
#include <esif/run/LandmarkIdRequirement.h>

#include <algorithm>

namespace esif
{
bool hasAnyLandmarkId(const Rawlog& log)
{
	if (log.any_landmark_id) return true;
	for (const auto& step : log.steps)
		if (step.scan)
			for (const auto& m : step.scan->measurements)
				if (m.id) return true;
	return false;
}

void requireLandmarkIds(const FilterPlugin& plugin, const Rawlog& log, const LandmarkIdSource& source)
{
	if (!plugin.needsLandmarkIds() || hasAnyLandmarkId(log)) return;
	const std::string head =
		source.config_path + ": plugin " + iniClassName(plugin) + " needs landmark IDs, but ";
	// The recorded run rejected every measurement: pointing at associations_from again would not help.
	if (!source.associations_file.empty())
		throw ConfigError(head + "the associations " + source.associations_file + " give none (every measurement rejected)");
	throw ConfigError(
		head + "the rawlog " + log.path + " has none" + (source.ids_hidden ? " (hide_landmark_ids = true)" : "") +
		": set [esif] associations_from = <a run folder, or in esif compare the label of another config> to use "
		"that run's data association");
}

std::optional<LandmarkId> largestInputLandmarkId(const Rawlog& log, const RecordedAssociations* recorded)
{
	std::optional<LandmarkId> largest;
	const auto consider = [&largest](LandmarkId id) { largest = std::max(largest.value_or(id), id); };
	if (recorded)
	{
		for (const auto& step : recorded->steps)
			for (const auto& a : step.associations)
				if (a.kind != Association::Kind::Rejected) consider(a.id);
		return largest;
	}
	if (!hasAnyLandmarkId(log)) return std::nullopt;  // none, or hidden (hide_landmark_ids)
	for (const auto& ids : log.true_ids)
		for (const auto& id : ids)
			if (id) consider(*id);
	for (const auto& step : log.steps)
		if (step.scan)
			for (const auto& m : step.scan->measurements)
				if (m.id) consider(*m.id);
	return largest;
}

}  // namespace esif
