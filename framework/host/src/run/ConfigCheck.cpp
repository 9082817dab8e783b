#include <esif/run/ConfigCheck.h>

#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/loader/PluginLoader.h>
#include <esif/run/RunConfig.h>

#include <filesystem>

namespace esif
{
namespace
{
/// `message` naming `config` (errors from the plugin loader name no file).
std::string namingConfig(const std::string& config, const std::string& message)
{
	return message.find(config) != std::string::npos ? message : config + ": " + message;
}
}  // namespace

std::vector<CheckedConfig> checkConfigs(const std::vector<std::string>& configs,
										const std::optional<std::string>& plugin_dir, bool local_maps)
{
	for (const auto& c : configs)
		if (!std::filesystem::is_regular_file(c)) throw ConfigError(c + ": config file not found");
	auto loader = PluginLoader::withExtraFolder(plugin_dir);
	loader.loadAll();
	std::vector<CheckedConfig> checked;
	for (const auto& c : configs)
	{
		try
		{
			const ConfigFile config = ConfigFile::load(c);
			const HostParams host = loadHostParams(config);
			const auto plugin = createConfiguredPlugin(config, host, loader);
			if (local_maps) requireLocalMapJoiner(*plugin, config.origin(), host.plugin);
			checked.push_back({host.plugin, plugin->formulation()});
		}
		catch (const ConfigError& e)
		{
			throw ConfigError(namingConfig(c, e.what()));
		}
	}
	return checked;
}

}  // namespace esif
