#pragma once
/// \file PluginName.h
/// A plugin's class as an INI file names it in `[esif] plugin`.

#include <esif/plugin/FilterPlugin.h>

#include <string>

namespace esif
{
/// "EkfSlam", not "esif::EkfSlam".
std::string iniClassName(const FilterPlugin& plugin);
/// The same for a registered class name ("esif::EkfSlam" -> "EkfSlam").
std::string iniClassName(const std::string& registered_name);

}  // namespace esif
