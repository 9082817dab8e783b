#include <esif/loader/PluginName.h>

namespace esif
{
namespace
{
const std::string kNamespacePrefix = "esif::";

bool hasNamespacePrefix(const std::string& name) { return name.rfind(kNamespacePrefix, 0) == 0; }
}  // namespace

std::string iniClassName(const std::string& registered_name)
{
	return hasNamespacePrefix(registered_name) ? registered_name.substr(kNamespacePrefix.size()) : registered_name;
}

std::string registeredClassName(const std::string& class_name)
{
	return hasNamespacePrefix(class_name) ? class_name : kNamespacePrefix + class_name;
}

std::string iniClassName(const FilterPlugin& plugin) { return iniClassName(plugin.GetRuntimeClass()->className); }

}  // namespace esif
