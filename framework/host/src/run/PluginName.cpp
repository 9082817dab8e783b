#include <esif/run/PluginName.h>

namespace esif
{
std::string iniClassName(const std::string& registered_name)
{
	const std::string prefix = "esif::";
	return registered_name.rfind(prefix, 0) == 0 ? registered_name.substr(prefix.size()) : registered_name;
}

std::string iniClassName(const FilterPlugin& plugin) { return iniClassName(plugin.GetRuntimeClass()->className); }

}  // namespace esif
