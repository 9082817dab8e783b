#include <esif/run/PluginName.h>

namespace esif
{
std::string iniClassName(const FilterPlugin& plugin)
{
	const std::string name = plugin.GetRuntimeClass()->className;
	const std::string prefix = "esif::";
	return name.rfind(prefix, 0) == 0 ? name.substr(prefix.size()) : name;
}

}  // namespace esif
