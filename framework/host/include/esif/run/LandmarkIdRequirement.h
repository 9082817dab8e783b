#pragma once
/// \file LandmarkIdRequirement.h
/// The host's check that a plugin which cannot associate measurements itself
/// (FilterPlugin::needsLandmarkIds, e.g. a full-SLAM optimizer) is given
/// landmark IDs: otherwise it would map nothing, and the run would look like
/// a result rather than a configuration mistake.

#include <esif/formats/AssociationFile.h>
#include <esif/formats/RawlogReader.h>
#include <esif/plugin/FilterPlugin.h>

#include <optional>
#include <string>

namespace esif
{
/// Where the landmark IDs of a run's input come from, for the error message.
struct LandmarkIdSource
{
	std::string config_path;  ///< the run's INI file
	bool ids_hidden = false;  ///< [esif] hide_landmark_ids = true
	std::string associations_file;	///< associations.txt applied to the rawlog; empty when none
};

/// Whether any measurement of `log` carries a landmark ID: as the read
/// found them (Rawlog::any_landmark_id), or in a step kept.
bool hasAnyLandmarkId(const Rawlog& log);

/// Throws ConfigError when `plugin` needs landmark IDs and no measurement of
/// `log` has one, naming the config, the plugin class, the rawlog (or the
/// associations file that left none) and the fix: `[esif] associations_from`.
void requireLandmarkIds(const FilterPlugin& plugin, const Rawlog& log, const LandmarkIdSource& source);

/// The largest landmark ID a measurement reaches the plugin with: the
/// recorded association's when one is given, else the rawlog's (none when
/// hidden); nullopt when no measurement carries one. The host hands it to
/// FilterPlugin::reserveLandmarkIds before the first step.
std::optional<LandmarkId> largestInputLandmarkId(const Rawlog& log, const RecordedAssociations* recorded);

}  // namespace esif
