#pragma once
/// \file PluginName.h
/// A plugin's class as an INI file names it in `[esif] plugin`, and as MRPT
/// registers it (in the esif namespace): the one place that knows the prefix.

#include <esif/plugin/FilterPlugin.h>

#include <string>

namespace esif
{
/// "EkfSlam", not "esif::EkfSlam".
std::string iniClassName(const FilterPlugin& plugin);
/// The same for a registered class name ("esif::EkfSlam" -> "EkfSlam").
std::string iniClassName(const std::string& registered_name);
/// The class as MRPT registers it, from either form ("EkfSlam" or "esif::EkfSlam" -> "esif::EkfSlam").
std::string registeredClassName(const std::string& class_name);

}  // namespace esif
