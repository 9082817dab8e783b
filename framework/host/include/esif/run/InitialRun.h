#pragma once
/// \file InitialRun.h
/// `[esif] initial_run`: another run's estimate as the starting point of a
/// plugin that takes one (FilterPlugin::usesInitialEstimate). The host
/// reads the run folder and hands the estimate over, so no plugin reads
/// files.

#include <esif/config/ConfigFile.h>
#include <esif/plugin/InitialEstimate.h>
#include <esif/plugin/FilterPlugin.h>
#include <esif/run/HostParams.h>

#include <optional>

namespace esif
{
/// ConfigError naming the key when the config gives `initial_run` to a
/// plugin that does not start from one (it would be ignored silently).
void requireInitialRunUse(const ConfigFile& cfg, const HostParams& host, const FilterPlugin& plugin);

/// The estimate of the run folder `[esif] initial_run` names (its
/// trajectory.tum and landmarks.txt), read before the rawlog so that a
/// wrong folder fails at once; nullopt when the key is empty. InputError
/// naming the key and the file when the folder is missing or malformed.
std::optional<InitialEstimate> readInitialRun(const ConfigFile& cfg, const HostParams& host);

/// InputError naming the key when `estimate` holds fewer poses than the
/// rawlog's `steps` (the run of another rawlog): said before the replay
/// rather than at the first step past its end.
void requireInitialRunCovers(const ConfigFile& cfg, const InitialEstimate& estimate, std::size_t steps);

}  // namespace esif
